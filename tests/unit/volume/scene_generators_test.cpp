#include "app/volume/scene_generators.h"

#include <cstring>

#include <gtest/gtest.h>

#include "app/core/parallel_for.h"

namespace cb {
namespace {

bool sameBytes(const Volume& a, const Volume& b) {
  return a.dims() == b.dims() &&
         std::memcmp(a.toDense().data(), b.toDense().data(), a.voxelCount() * sizeof(float)) == 0;
}

TEST(SceneGenerators, BundledCumulusFillsRoughlyThirtyPercent) {
  Volume v = makeBundledCumulus(glm::ivec3(64), 1);
  double f = filledFraction(v);
  EXPECT_GT(f, 0.22);
  EXPECT_LT(f, 0.38);
  // Dense inside, empty in the corners, flat base: nothing below y = -0.45.
  EXPECT_GT(v.at(32, 20, 32), 0.9f);
  EXPECT_EQ(v.at(0, 0, 0), 0.0f);
  EXPECT_EQ(v.at(63, 63, 63), 0.0f);
  for (int z = 0; z < 64; ++z)
    for (int x = 0; x < 64; ++x) ASSERT_EQ(v.at(x, 16, z), 0.0f) << x << "," << z;
}

TEST(SceneGenerators, SparsePuffsFillUnderThreePercentButNotNothing) {
  Volume v = makeSparsePuffs(glm::ivec3(64), 2);
  double f = filledFraction(v);
  EXPECT_GT(f, 0.002);
  EXPECT_LT(f, 0.03);
}

TEST(SceneGenerators, SameSeedSameBytesOnAnyThreadCountOtherSeedDiffers) {
  setWorkerThreads(1);
  Volume a = makeBundledCumulus(glm::ivec3(48), 3);
  Volume p = makeSparsePuffs(glm::ivec3(48), 3);
  setWorkerThreads(8);
  Volume b = makeBundledCumulus(glm::ivec3(48), 3);
  Volume q = makeSparsePuffs(glm::ivec3(48), 3);
  setWorkerThreads(0);
  EXPECT_TRUE(sameBytes(a, b));
  EXPECT_TRUE(sameBytes(p, q));
  EXPECT_FALSE(sameBytes(a, makeBundledCumulus(glm::ivec3(48), 4)));
  EXPECT_FALSE(sameBytes(p, makeSparsePuffs(glm::ivec3(48), 4)));
}

TEST(SceneGenerators, SingleVoxelAndSphere) {
  Volume s = makeSingleVoxel(glm::ivec3(16), {3, 4, 5}, 0.75f);
  EXPECT_EQ(s.at(3, 4, 5), 0.75f);
  EXPECT_NEAR(filledFraction(s), 1.0 / 4096.0, 1e-12);
  Volume sp = makeSphere(glm::ivec3(32), glm::vec3(0.0f), 0.5f, 1.0f, 0.2f);
  EXPECT_EQ(sp.at(16, 16, 16), 1.0f);
  EXPECT_EQ(sp.at(16, 16, 29), 0.0f);  // world z ≈ 0.84, outside radius 0.5
  // Volume of a radius-0.5 ball in the 8-unit box ≈ 6.5%.
  EXPECT_NEAR(filledFraction(sp), 4.18879 * 0.125 / 8.0, 0.01);
}

}  // namespace
}  // namespace cb
