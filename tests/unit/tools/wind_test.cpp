// Wind: zero velocity is the identity (bit for bit), a uniform wind carries the cloud's centre of
// mass by velocity × time and keeps its mass, dissipation fades it as exp(−rate·t), projection
// lowers the divergence a force creates, the same inputs give the same bytes on 1, 2 and 8
// threads, and the steps and the resampling give the bytes of their formulas written out plainly
// (with the AVX2 kernels and without).
#include "app/tools/wind.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "app/core/parallel_for.h"
#include "app/tools/wind_kernels.h"

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
// start sampled trilinearly there (0 outside), each lerp a + (b − a)·t in x, y, z order, times
// fade. `outside` counts the voxels whose eight samples are not all within one voxel of the box.
Volume resampledByTheFormula(const WindSolver& wind, const Volume& start, float fade = 1.0f,
                             int* outside = nullptr) {
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
        if (outside &&
            (glm::any(glm::lessThan(j, glm::ivec3(-1))) || glm::any(glm::greaterThanEqual(j, d))))
          ++*outside;
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
                 g.z) *
            fade;
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

// The seed of the randomized tests: CB_TEST_SEED when set, else 1; printed.
uint32_t testSeed() {
  uint32_t seed = 1;
  if (const char* e = std::getenv("CB_TEST_SEED")) seed = uint32_t(std::stoul(e));
  std::printf("wind_test: seed %u (CB_TEST_SEED)\n", seed);
  return seed;
}

// Rows of eight voxels take the AVX2 read when their samples lie within a voxel of the box and
// the bounds-checked one when one does not; a block narrower than eight is read voxel by voxel;
// cells coarser and finer than the voxels.
TEST(Wind, ResamplingGivesTheFormulasBytesAtTheFacesAndInPartBlocks) {
  std::mt19937 random(testSeed());
  auto uniform = [&](float lo, float hi) {
    return std::uniform_real_distribution<float>(lo, hi)(random);
  };
  struct Case {
    glm::ivec3 dims, cells;
  };
  for (const Case& c : {Case{{48, 40, 32}, {13, 11, 9}}, Case{{45, 38, 29}, {24, 24, 24}},
                        Case{{16, 24, 13}, {40, 30, 20}}}) {
    SCOPED_TRACE("dims " + std::to_string(c.dims.x) + "x" + std::to_string(c.dims.y) + "x" +
                 std::to_string(c.dims.z));
    // Density up to the faces, with holes.
    Volume start(c.dims, glm::vec3(-1.0f, -0.5f, -0.8f), glm::vec3(1.2f, 0.6f, 0.4f));
    for (int z = 0; z < c.dims.z; ++z)
      for (int y = 0; y < c.dims.y; ++y)
        for (int x = 0; x < c.dims.x; ++x)
          if (uniform(0.0f, 1.0f) < 0.7f) start.voxelForWrite(x, y, z) = uniform(0.0f, 1.0f);
    WindParams params;
    params.grid = c.cells;
    params.dissipation = 0.3f;
    WindSolver wind(start.worldMin(), start.worldMax(), params);
    // A wind of a few voxels per step, so samples leave the box.
    wind.setUniformWind(
        glm::vec3(uniform(-1.5f, 1.5f), uniform(-1.0f, 1.0f), uniform(-1.0f, 1.0f)));
    wind.addForce(glm::vec3(uniform(-3, 3), uniform(-3, 3), uniform(-3, 3)),
                  glm::vec3(uniform(-0.5f, 0.5f), uniform(-0.2f, 0.2f), uniform(-0.4f, 0.0f)), 0.6f,
                  0.1f);
    for (int i = 0; i < 5; ++i) wind.step(0.05f);
    int outside = 0;
    const float fade = float(std::exp(-double(params.dissipation) * wind.elapsed()));
    const Volume expected = resampledByTheFormula(wind, start, fade, &outside);
    EXPECT_GT(outside, 0);
    for (bool avx2 : {true, false}) {
      SCOPED_TRACE(avx2 ? "AVX2 where the CPU has it" : "scalar");
      wind::allowAvx2(avx2);
      Volume shown(start.dims(), start.worldMin(), start.worldMax());
      wind.resampleDensity(start, &shown, shown.bounds());
      EXPECT_TRUE(sameBytes(shown, expected));
      Volume every(start.dims(), start.worldMin(), start.worldMax());
      wind.resampleDensity(start, &every, every.bounds(), true);
      EXPECT_TRUE(sameBytes(every, expected));
    }
    wind::allowAvx2(true);
  }
}

// WindSolver::step written out plainly, one cell at a time (wind.h's formulas in the order the
// solver states them): the reference for its row kernels and fused passes.
class PlainWind {
 public:
  PlainWind(glm::ivec3 n, glm::vec3 cell, int iterations)
      : n_(n),
        cell_(cell),
        iterations_(iterations),
        u_(size_t(n.x) * n.y * n.z),
        d_(u_.size(), glm::vec3(0)) {}

  // The solver's velocity (after forces, which are not under test here).
  void takeVelocity(const WindSolver& wind) {
    each([&](int x, int y, int z) { u_[index(x, y, z)] = wind.velocityAt({x, y, z}); });
  }
  glm::vec3 velocity(int x, int y, int z) const { return u_[index(x, y, z)]; }
  glm::vec3 displacement(int x, int y, int z) const { return d_[index(x, y, z)]; }

  void step(float dt) {
    // u(x) ← u(x − u(x)·dt).
    std::vector<glm::vec3> moved(u_.size());
    each([&](int x, int y, int z) {
      moved[index(x, y, z)] = sample(u_, glm::vec3(x, y, z) - u_[index(x, y, z)] * dt / cell_);
    });
    u_ = moved;
    // ∇·u by central differences (the border cell repeated), Jacobi sweeps from p = 0 with p = 0
    // outside, u ← u − ∇p.
    auto u = [&](int x, int y, int z) {
      return u_[index(std::clamp(x, 0, n_.x - 1), std::clamp(y, 0, n_.y - 1),
                      std::clamp(z, 0, n_.z - 1))];
    };
    std::vector<float> div(u_.size()), p(u_.size(), 0.0f), next(u_.size());
    each([&](int x, int y, int z) {
      div[index(x, y, z)] = (u(x + 1, y, z).x - u(x - 1, y, z).x) / (2 * cell_.x) +
                            (u(x, y + 1, z).y - u(x, y - 1, z).y) / (2 * cell_.y) +
                            (u(x, y, z + 1).z - u(x, y, z - 1).z) / (2 * cell_.z);
    });
    auto P = [&](int x, int y, int z) {
      const bool inside = x >= 0 && y >= 0 && z >= 0 && x < n_.x && y < n_.y && z < n_.z;
      return inside ? p[index(x, y, z)] : 0.0f;
    };
    const glm::vec3 inv_h2 = 1.0f / (cell_ * cell_);
    const float diagonal = 2.0f * (inv_h2.x + inv_h2.y + inv_h2.z);
    for (int i = 0; i < iterations_; ++i) {
      each([&](int x, int y, int z) {
        next[index(x, y, z)] =
            ((P(x - 1, y, z) + P(x + 1, y, z)) * inv_h2.x +
             (P(x, y - 1, z) + P(x, y + 1, z)) * inv_h2.y +
             (P(x, y, z - 1) + P(x, y, z + 1)) * inv_h2.z - div[index(x, y, z)]) /
            diagonal;
      });
      p.swap(next);
    }
    each([&](int x, int y, int z) {
      u_[index(x, y, z)] -= glm::vec3((P(x + 1, y, z) - P(x - 1, y, z)) / (2 * cell_.x),
                                      (P(x, y + 1, z) - P(x, y - 1, z)) / (2 * cell_.y),
                                      (P(x, y, z + 1) - P(x, y, z - 1)) / (2 * cell_.z));
    });
    // D(x) ← D(x − u(x)·dt) − u(x)·dt.
    std::vector<glm::vec3> carried(d_.size());
    each([&](int x, int y, int z) {
      const glm::vec3 v = u_[index(x, y, z)];
      carried[index(x, y, z)] = sample(d_, glm::vec3(x, y, z) - v * dt / cell_) - v * dt;
    });
    d_ = carried;
  }

 private:
  size_t index(int x, int y, int z) const { return (size_t(z) * n_.y + y) * n_.x + x; }
  template <typename Fn>
  void each(Fn fn) const {
    for (int z = 0; z < n_.z; ++z)
      for (int y = 0; y < n_.y; ++y)
        for (int x = 0; x < n_.x; ++x) fn(x, y, z);
  }
  // Trilinear at continuous cell index c, clamped to the border cells.
  glm::vec3 sample(const std::vector<glm::vec3>& g, glm::vec3 c) const {
    auto lerp = [](glm::vec3 a, glm::vec3 b, float t) { return a + (b - a) * t; };
    c = glm::clamp(c, glm::vec3(0), glm::vec3(n_ - 1));
    const glm::ivec3 i0 = glm::min(glm::ivec3(glm::floor(c)), glm::max(n_ - 2, glm::ivec3(0)));
    const glm::ivec3 i1 = glm::min(i0 + 1, n_ - 1);
    const glm::vec3 f = c - glm::vec3(i0);
    auto G = [&](int x, int y, int z) { return g[index(x, y, z)]; };
    return lerp(lerp(lerp(G(i0.x, i0.y, i0.z), G(i1.x, i0.y, i0.z), f.x),
                     lerp(G(i0.x, i1.y, i0.z), G(i1.x, i1.y, i0.z), f.x), f.y),
                lerp(lerp(G(i0.x, i0.y, i1.z), G(i1.x, i0.y, i1.z), f.x),
                     lerp(G(i0.x, i1.y, i1.z), G(i1.x, i1.y, i1.z), f.x), f.y),
                f.z);
  }

  glm::ivec3 n_;
  glm::vec3 cell_;
  int iterations_;
  std::vector<glm::vec3> u_, d_;
};

bool sameBits(glm::vec3 a, glm::vec3 b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Rows longer and shorter than eight cells, not multiples of eight, one cell wide; winds of up
// to a few cells a step (backtraces past the borders); 0 and several Jacobi sweeps.
TEST(Wind, StepsGiveThePlainFormulasBytes) {
  std::mt19937 random(testSeed());
  auto uniform = [&](float lo, float hi) {
    return std::uniform_real_distribution<float>(lo, hi)(random);
  };
  auto vec = [&](float r) { return glm::vec3(uniform(-r, r), uniform(-r, r), uniform(-r, r)); };
  const glm::ivec3 grids[] = {{24, 24, 24}, {21, 9, 13}, {37, 6, 5},
                              {5, 7, 3},    {1, 4, 2},   {9, 1, 1}};
  for (bool avx2 : {true, false}) {
    SCOPED_TRACE(avx2 ? "AVX2 where the CPU has it" : "scalar");
    wind::allowAvx2(avx2);
    for (const glm::ivec3 grid : grids) {
      SCOPED_TRACE("grid " + std::to_string(grid.x) + "x" + std::to_string(grid.y) + "x" +
                   std::to_string(grid.z));
      WindParams params;
      params.grid = grid;
      params.pressure_iterations = int(random() % 3) * 10 + (grid.x == 24 ? 20 : 0);
      const glm::vec3 world_min = vec(1.0f), world_max = world_min + glm::vec3(2, 1, 1.5f);
      WindSolver wind(world_min, world_max, params);
      PlainWind plain(grid, wind.cellSize(), params.pressure_iterations);
      int differing = 0;
      for (int segment = 0; segment < 2; ++segment) {
        wind.setUniformWind(vec(0.6f));
        wind.addForce(vec(4.0f), 0.5f * (world_min + world_max) + vec(0.3f), 0.7f, 0.1f);
        plain.takeVelocity(wind);
        for (int i = 0; i < 4; ++i) {
          const float dt = uniform(0.02f, 0.1f);
          wind.step(dt);
          plain.step(dt);
        }
        for (int z = 0; z < grid.z; ++z)
          for (int y = 0; y < grid.y; ++y)
            for (int x = 0; x < grid.x; ++x)
              differing += !sameBits(wind.velocityAt({x, y, z}), plain.velocity(x, y, z)) +
                           !sameBits(wind.displacementAt({x, y, z}), plain.displacement(x, y, z));
      }
      EXPECT_EQ(differing, 0);
    }
  }
  wind::allowAvx2(true);
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
