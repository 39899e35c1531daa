// Wind: zero velocity is the identity (bit for bit), a uniform wind carries the cloud's centre of
// mass by velocity × time and keeps its mass, dissipation fades it as exp(−rate·t), projection
// lowers the divergence a force creates, and the same inputs give the same bytes on 1, 2 and 8
// threads.
#include "app/tools/wind.h"

#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "app/core/parallel_for.h"

namespace cb {
namespace {

constexpr int kDensity = 96;
WindParams coarse() {
  WindParams p;
  p.grid = glm::ivec3(24);
  return p;
}

Volume ball(glm::vec3 centre_voxels, float radius) {
  Volume v{glm::ivec3(kDensity)};
  for (int z = 0; z < kDensity; ++z)
    for (int y = 0; y < kDensity; ++y)
      for (int x = 0; x < kDensity; ++x) {
        const float r = glm::distance(glm::vec3(x, y, z) + 0.5f, centre_voxels);
        if (r < radius) v.voxelForWrite(x, y, z) = 0.8f * (1.0f - r / radius);
      }
  return v;
}

double mass(const Volume& v) {
  double s = 0;
  {
    const std::vector<float> v_dense = v.toDense();
    for (size_t i = 0; i < v.voxelCount(); ++i) s += v_dense[i];
  }
  return s;
}

glm::dvec3 centreOfMassWorld(const Volume& v) {
  glm::dvec3 s(0);
  const glm::ivec3 d = v.dims();
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x)
        s += double(v.at(x, y, z)) * glm::dvec3(v.voxelToWorld(glm::vec3(x, y, z) + 0.5f));
  return s / mass(v);
}

bool sameBytes(const Volume& a, const Volume& b) {
  return std::memcmp(a.toDense().data(), b.toDense().data(), a.voxelCount() * sizeof(float)) == 0;
}

// `steps` steps of dt, then the density shown: the start carried by the flow map.
void blow(WindSolver* wind, Volume* v, int steps, float dt) {
  const Volume start = *v;
  for (int i = 0; i < steps; ++i) wind->step(dt);
  wind->resampleDensity(start, v, v->bounds());
}

TEST(Wind, ZeroVelocityChangesNothing) {
  const Volume before = ball({40, 50, 47}, 20);
  Volume v = before;
  WindSolver wind(v.worldMin(), v.worldMax(), coarse());
  blow(&wind, &v, 3, 1.0f / 15);
  EXPECT_TRUE(sameBytes(v, before));
  // And the step-by-step advection of specification 1.1 records.
  for (int i = 0; i < 3; ++i) wind.advectDensityEveryVoxel(1.0f / 15, &v);
  EXPECT_TRUE(sameBytes(v, before));
}

TEST(Wind, UniformWindMovesTheCentreOfMass) {
  Volume v = ball({40, 50, 47}, 16);
  const glm::dvec3 c0 = centreOfMassWorld(v);
  const double m0 = mass(v);
  WindSolver wind(v.worldMin(), v.worldMax(), coarse());
  const glm::vec3 velocity(0.25f, -0.1f, 0.05f);  // world units per second
  wind.setUniformWind(velocity);
  const float dt = 0.05f;
  blow(&wind, &v, 12, dt);
  // The uniform field is divergence-free: projection leaves it alone.
  EXPECT_EQ(wind.velocityAt({3, 20, 11}), velocity);
  const glm::dvec3 moved = centreOfMassWorld(v) - c0;
  const glm::dvec3 expected = glm::dvec3(velocity) * double(12 * dt);  // 0.15, −0.06, 0.03
  EXPECT_NEAR(moved.x, expected.x, 0.005);
  EXPECT_NEAR(moved.y, expected.y, 0.005);
  EXPECT_NEAR(moved.z, expected.z, 0.005);
  // Without dissipation the mass stays (trilinear weights of a uniform shift sum to 1).
  EXPECT_NEAR(mass(v) / m0, 1.0, 0.01);
}

TEST(Wind, DissipationFadesTheDensity) {
  Volume v = ball({48, 48, 48}, 16);
  const double m0 = mass(v);
  WindParams p = coarse();
  p.dissipation = 0.5f;
  WindSolver wind(v.worldMin(), v.worldMax(), p);
  blow(&wind, &v, 10, 0.1f);
  EXPECT_NEAR(mass(v) / m0, std::exp(-0.5), 1e-3);
}

TEST(Wind, ProjectionLowersTheDivergenceOfAForce) {
  WindSolver wind(glm::vec3(-1), glm::vec3(1), coarse());
  wind.addForce({3, 0, 0}, glm::vec3(0), 0.5f, 0.1f);
  const float before = wind.maxDivergence();
  ASSERT_GT(before, 0.1f);
  wind.stepVelocity(0.0f);  // no motion: projection only
  EXPECT_LT(wind.maxDivergence(), 0.5f * before);
}

Volume windyRun() {
  Volume v = ball({40, 50, 47}, 20);
  WindSolver wind(v.worldMin(), v.worldMax(), coarse());
  wind.setUniformWind({0.1f, 0.0f, 0.0f});
  wind.addForce({0, 2, 1}, glm::vec3(-0.2f, 0.1f, 0.0f), 0.6f, 0.1f);
  blow(&wind, &v, 4, 0.05f);
  return v;
}

// The flow map's density written out as its formula (seed 004 Eq. 3.7 through the flow map):
// the displacement interpolated trilinearly from the cells (clamped to the border cells), the
// start sampled trilinearly there (0 outside), each lerp a + (b − a)·t in x, y, z order.
Volume resampledByTheFormula(const WindSolver& wind, const Volume& start) {
  const glm::ivec3 n = wind.grid(), d = start.dims();
  const glm::vec3 vs = start.voxelSize(), to_cells = vs / wind.cellSize();
  const glm::vec3 offset = 0.5f * to_cells - 0.5f;
  auto lerp = [](auto a, auto b, float t) { return a + (b - a) * t; };
  Volume out(d, start.worldMin(), start.worldMax());
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        const glm::vec3 v(x, y, z);
        const glm::vec3 c = glm::clamp(v * to_cells + offset, glm::vec3(0), glm::vec3(n - 1));
        const glm::ivec3 i0 = glm::min(glm::ivec3(glm::floor(c)), glm::max(n - 2, glm::ivec3(0)));
        const glm::ivec3 i1 = glm::min(i0 + 1, n - 1);
        const glm::vec3 f = c - glm::vec3(i0);
        auto D = [&](int i, int j, int k) { return wind.displacementAt({i, j, k}); };
        const glm::vec3 disp = lerp(lerp(lerp(D(i0.x, i0.y, i0.z), D(i1.x, i0.y, i0.z), f.x),
                                         lerp(D(i0.x, i1.y, i0.z), D(i1.x, i1.y, i0.z), f.x), f.y),
                                    lerp(lerp(D(i0.x, i0.y, i1.z), D(i1.x, i0.y, i1.z), f.x),
                                         lerp(D(i0.x, i1.y, i1.z), D(i1.x, i1.y, i1.z), f.x), f.y),
                                    f.z);
        const glm::vec3 p = v + disp / vs;
        const glm::ivec3 j = glm::ivec3(glm::floor(p));
        const glm::vec3 g = p - glm::vec3(j);
        auto S = [&](int i, int jj, int k) {
          const bool inside = i >= 0 && jj >= 0 && k >= 0 && i < d.x && jj < d.y && k < d.z;
          return inside ? start.at(i, jj, k) : 0.0f;
        };
        const float rho =
            lerp(lerp(lerp(S(j.x, j.y, j.z), S(j.x + 1, j.y, j.z), g.x),
                      lerp(S(j.x, j.y + 1, j.z), S(j.x + 1, j.y + 1, j.z), g.x), g.y),
                 lerp(lerp(S(j.x, j.y, j.z + 1), S(j.x + 1, j.y, j.z + 1), g.x),
                      lerp(S(j.x, j.y + 1, j.z + 1), S(j.x + 1, j.y + 1, j.z + 1), g.x), g.y),
                 g.z);
        if (rho != 0.0f) out.voxelForWrite(x, y, z) = rho;
      }
  return out;
}

// The resampling's tables, dense copy and block skipping give the formula's bytes; the copy
// of the start it keeps follows a start that changed (a new generation) or another start.
TEST(Wind, ResamplingGivesTheFormulasBytesAndFollowsANewStart) {
  Volume start = ball({40, 50, 47}, 20);
  WindSolver wind(start.worldMin(), start.worldMax(), coarse());
  wind.setUniformWind({0.1f, 0.02f, 0.0f});
  wind.addForce({0, 2, 1}, glm::vec3(-0.2f, 0.1f, 0.0f), 0.6f, 0.1f);
  for (int i = 0; i < 6; ++i) wind.step(0.05f);
  Volume shown(start.dims(), start.worldMin(), start.worldMax());
  VoxelBox written = wind.resampleDensity(start, &shown, shown.bounds());
  EXPECT_TRUE(sameBytes(shown, resampledByTheFormula(wind, start)));
  // The start changes (a second ball): the next frame reads it, not the copy kept.
  for (int z = 10; z < 20; ++z)
    for (int y = 10; y < 20; ++y)
      for (int x = 60; x < 70; ++x) start.voxelForWrite(x, y, z) = 0.5f;
  start.markDirty({{60, 10, 10}, {70, 20, 20}});
  written = wind.resampleDensity(start, &shown, written);
  const Volume expected = resampledByTheFormula(wind, start);
  EXPECT_TRUE(sameBytes(shown, expected));
  const Volume other = ball({50, 40, 50}, 12);
  wind.resampleDensity(other, &shown, written);
  EXPECT_TRUE(sameBytes(shown, resampledByTheFormula(wind, other)));
}

TEST(Wind, SameBytesOnAnyThreadCount) {
  setWorkerThreads(1);
  const Volume one = windyRun();
  setWorkerThreads(2);
  const Volume two = windyRun();
  setWorkerThreads(8);
  const Volume eight = windyRun();
  setWorkerThreads(0);
  EXPECT_TRUE(sameBytes(one, two));
  EXPECT_TRUE(sameBytes(one, eight));
  EXPECT_FALSE(sameBytes(one, ball({40, 50, 47}, 20)));  // the wind did move it
}

}  // namespace
}  // namespace cb
