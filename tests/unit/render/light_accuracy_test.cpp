// The light volume against the reference march of Alg. 5 at the product's 256³, the size
// `cloudbrush bench render` measures (its "light MAE vs reference march" target, ≤ 0.01), over
// the voxels the renderer reads (light_accuracy.h).
#include "app/render/light_accuracy.h"

#include <cstdio>

#include <gtest/gtest.h>

#include "app/volume/scene_generators.h"

namespace cb {
namespace {

// The bench's bound on the mean absolute error (bench_render.cpp, the light volume target).
constexpr double kMaxMeanError = 0.01;
// Over the voxels the reference does not light fully: the sweep's bilinear footprint blurs the
// shadow's edge by about a voxel, so the error concentrates there (0.006 measured at 256³ with
// the default sun, 0.22 when the unstored shadow below the cloud was counted).
constexpr double kMaxShadowedMeanError = 0.02;
// Every 64th z slice of the reference (4 slices through the cloud; the bench takes every 32nd):
// the march is O(voxels × edge), ~0.3 s a slice.
constexpr int kReferenceZStep = 64;

TEST(LightAccuracy, SweepMatchesTheReferenceMarchAt256OnTheVoxelsTheRendererReads) {
  const Volume cumulus = makeBundledCumulus(glm::ivec3(256), 1);
  const Light light;  // the default sun, as the bench
  LightVolume lv;
  sweepLightVolume(lv, cumulus, light, cumulus.bounds());
  const LightAccuracy a =
      compareWithReference(lv, cumulus, marchLightReference(cumulus, light, kReferenceZStep));
  std::printf("MAE %.4f over %zu voxels, %.4f over %zu shadowed, %zu not read\n", a.mae, a.voxels,
              a.shadowed_mae, a.shadowed_voxels, a.unread_voxels);
  // The comparison covers the cloud: the 4 slices cross 163k voxels of light bricks.
  EXPECT_GT(a.voxels, 100000u);
  EXPECT_GT(a.shadowed_voxels, 50000u);
  EXPECT_LE(a.mae, kMaxMeanError);
  EXPECT_LE(a.shadowed_mae, kMaxShadowedMeanError);
}

// The unstored shadow is outside the comparison, and only it: a voxel below the cloud that no
// light brick holds reads 1 (fully lit) while the reference has shadow there.
TEST(LightAccuracy, OnlyVoxelsOutsideTheLightBricksAreLeftOut) {
  Volume v(glm::ivec3(64));
  for (int z = 24; z < 40; ++z)
    for (int x = 24; x < 40; ++x)
      for (int y = 48; y < 56; ++y) v.voxelForWrite(x, y, z) = 1.0f;
  v.markDirty(v.bounds());
  Light light;
  light.direction = Light::directionTowards({0.0f, 10.0f, 0.0f});  // straight down
  LightVolume lv;
  sweepLightVolume(lv, v, light, v.bounds());
  const std::vector<float> ref = marchLightReference(v, light);
  EXPECT_LT(ref[v.index(32, 4, 32)], 0.5f) << "the reference shades the ground below";
  EXPECT_EQ(lv.at(32, 4, 32), 1.0f) << "the sweep stores no shadow that falls on nothing";
  const LightAccuracy a = compareWithReference(lv, v, ref);
  EXPECT_EQ(a.voxels + a.unread_voxels, size_t(v.voxelCount()));
  EXPECT_EQ(a.voxels, lightBrickList(v).size() * 16u * 16u * 16u);
  EXPECT_LT(a.mae, 1e-3);
}

}  // namespace
}  // namespace cb
