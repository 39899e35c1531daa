// The light at reduced resolution for light-ball drags (reduced_light_sweep.h): close to the full
// sweep where the cloud is, covering the cloud, a few megabytes however wide the cloud, and the
// same whether its block averages were kept from the sweep before or made anew.
#include "app/render/reduced_light_sweep.h"

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "app/volume/scene_generators.h"

namespace cb {
namespace {

// Mean absolute difference between the grid and the full sweep over the voxels holding density
// that the full sweep does not leave fully lit (where the preview's light is seen).
double shadowedMeanAbsoluteError(const Volume& v, const LightPreviewGrid& grid,
                                 const LightVolume& full) {
  double s = 0;
  size_t n = 0;
  for (const glm::ivec3 b : v.allocatedBrickList()) {
    const VoxelBox box = v.brickBox(b);
    for (int z = box.lo.z; z < box.hi.z; ++z)
      for (int y = box.lo.y; y < box.hi.y; ++y)
        for (int x = box.lo.x; x < box.hi.x; ++x) {
          const float ref = full.at(x, y, z);
          if (v.at(x, y, z) <= 0.0f || ref >= 0.999f) continue;
          s += std::abs(double(grid.sample(glm::vec3(x, y, z) + 0.5f)) - double(ref));
          ++n;
        }
  }
  return n ? s / double(n) : 0.0;
}

TEST(ReducedLightSweep, HalfResolutionIsCloseToTheFullSweepFromSeveralDirections) {
  Volume v = makeBundledCumulus(glm::ivec3(128), 1);
  ReducedLightSweep reduced;
  for (glm::vec3 pos :
       {glm::vec3(3.0f, 4.0f, 1.5f), glm::vec3(-4.0f, 1.0f, 2.0f), glm::vec3(0.5f, -3.0f, -3.0f)}) {
    Light light;
    light.direction = Light::directionTowards(pos);
    LightVolume full;
    sweepLightVolume(full, v, light, v.bounds());
    const LightPreviewGrid& grid = reduced.sweep(v, light, 2);
    EXPECT_EQ(grid.divisor, 2);
    const double error = shadowedMeanAbsoluteError(v, grid, full);
    std::printf("light towards (%.1f, %.1f, %.1f): mean |T - T_full| %.4f over shadowed cloud\n",
                pos.x, pos.y, pos.z, error);
    // 8 bits (±0.002) and the coarse grid's own error; measured 0.006–0.012.
    EXPECT_LT(error, 0.03) << pos.x << "," << pos.y << "," << pos.z;
    EXPECT_GT(error, 0.0) << "the coarse grid must differ somewhere (it is not the full sweep)";
  }
}

// Every allocated voxel's coarse position lies inside the grid's box (so the texture's edge
// clamp never stands in for the cloud's light), and a cloud spread over a wide sky is swept at
// a coarser divisor rather than into a grid of tens of megabytes.
TEST(ReducedLightSweep, TheGridCoversTheCloudAndStaysSmall) {
  for (const Volume& v :
       {makeBundledCumulus(glm::ivec3(128), 1), makeSparsePuffs(glm::ivec3(768, 128, 768), 5)}) {
    ReducedLightSweep reduced;
    const LightPreviewGrid& grid = reduced.sweep(v, Light{}, 2);
    const size_t voxels = size_t(grid.size.x) * size_t(grid.size.y) * size_t(grid.size.z);
    std::printf("dims %dx%dx%d: divisor %d, grid %dx%dx%d (%zu bytes)\n", v.dims().x, v.dims().y,
                v.dims().z, grid.divisor, grid.size.x, grid.size.y, grid.size.z, voxels);
    EXPECT_LE(voxels, ReducedLightSweep::kMaxGridVoxels);
    // The wide sky's puffs span it: at divisor 2 their box would hold ~9.4 M coarse voxels.
    if (v.dims().x == 768) {
      EXPECT_GT(grid.divisor, 2);
    }
    EXPECT_EQ(grid.bytes.size(), voxels);
    for (const glm::ivec3 b : v.allocatedBrickList()) {
      const VoxelBox box = v.brickBox(b);
      EXPECT_TRUE(glm::all(glm::greaterThanEqual(box.lo / grid.divisor, grid.lo)));
      EXPECT_TRUE(
          glm::all(glm::lessThanEqual((box.hi - 1) / grid.divisor, grid.lo + grid.size - 1)));
    }
  }
}

// A drag keeps the block averages while the volume stays: the second light's grid equals a new
// sweeper's; after an edit the averages are made anew (the grid follows the edit).
TEST(ReducedLightSweep, KeptAveragesGiveTheSameGridAsNewOnes) {
  Volume v = makeSparsePuffs(glm::ivec3(64), 5);
  Light first, second;
  first.direction = Light::directionTowards(glm::vec3(2.0f, 3.0f, 1.0f));
  second.direction = Light::directionTowards(glm::vec3(-1.0f, 3.0f, 2.0f));
  ReducedLightSweep dragged;
  const std::vector<uint8_t> at_first = dragged.sweep(v, first, 2).bytes;
  EXPECT_EQ(dragged.sweep(v, second, 2).bytes, ReducedLightSweep{}.sweep(v, second, 2).bytes);
  EXPECT_NE(dragged.sweep(v, second, 2).bytes, at_first) << "a new light must change the grid";
  const VoxelBox block{glm::ivec3(24), glm::ivec3(40)};
  for (int z = 24; z < 40; ++z)
    for (int y = 24; y < 40; ++y)
      for (int x = 24; x < 40; ++x) v.voxelForWrite(x, y, z) = 1.0f;
  v.markDirty(block);
  EXPECT_EQ(dragged.sweep(v, second, 2).bytes, ReducedLightSweep{}.sweep(v, second, 2).bytes);
}

}  // namespace
}  // namespace cb
