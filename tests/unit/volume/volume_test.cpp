#include "app/volume/volume.h"

#include <gtest/gtest.h>

namespace cb {
namespace {

TEST(VoxelBox, UniteIntersectAndEmpty) {
  VoxelBox a{{0, 0, 0}, {4, 4, 4}}, b{{2, 2, 2}, {6, 5, 8}}, e;
  EXPECT_TRUE(e.empty());
  EXPECT_EQ(a.unite(e), a);
  EXPECT_EQ(a.unite(b), (VoxelBox{{0, 0, 0}, {6, 5, 8}}));
  EXPECT_EQ(a.intersect(b), (VoxelBox{{2, 2, 2}, {4, 4, 4}}));
  EXPECT_TRUE(a.intersect(VoxelBox{{5, 5, 5}, {6, 6, 6}}).empty());
  EXPECT_EQ(a.voxelCount(), 64);
}

TEST(Volume, NewVolumeIsAllDirtyThenCleanForAConsumerThatCaughtUp) {
  Volume v({8, 8, 8});
  EXPECT_EQ(v.dirtySince(0), v.bounds());
  uint64_t seen = v.generation();
  EXPECT_TRUE(v.dirtySince(seen).empty());
}

TEST(Volume, DirtySinceIsTheUnionOfLaterChangesOnly) {
  Volume v({16, 16, 16});
  uint64_t g0 = v.generation();
  v.set(1, 2, 3, 0.5f);
  uint64_t g1 = v.generation();
  v.markDirty({{10, 10, 10}, {12, 12, 12}});
  EXPECT_EQ(v.dirtySince(g0), (VoxelBox{{1, 2, 3}, {12, 12, 12}}));
  EXPECT_EQ(v.dirtySince(g1), (VoxelBox{{10, 10, 10}, {12, 12, 12}}));
  EXPECT_FLOAT_EQ(v.at(1, 2, 3), 0.5f);
}

TEST(Volume, DirtyBoxesAreClippedToBounds) {
  Volume v({8, 8, 8});
  uint64_t g = v.generation();
  v.markDirty({{-4, 6, 6}, {2, 20, 20}});
  EXPECT_EQ(v.dirtySince(g), (VoxelBox{{0, 6, 6}, {2, 8, 8}}));
  uint64_t g2 = v.generation();
  v.markDirty({{20, 20, 20}, {30, 30, 30}});
  EXPECT_EQ(v.generation(), g2) << "a change entirely outside is not a change";
}

TEST(Volume, AConsumerFarBehindGetsTheWholeVolume) {
  Volume v({8, 8, 8});
  uint64_t g = v.generation();
  for (int i = 0; i < 1000; ++i) v.set(i % 8, 0, 0, 1.0f);
  EXPECT_EQ(v.dirtySince(g), v.bounds());
}

TEST(Volume, WorldVoxelMappingIsConsistent) {
  Volume v({256, 256, 256});
  glm::vec3 w = v.voxelToWorld(glm::vec3(128.0f));
  EXPECT_NEAR(w.x, 0.0f, 1e-6);
  glm::vec3 back = v.worldToVoxel(glm::vec3(0.5f, -1.0f, 1.0f));
  EXPECT_NEAR(back.x, 192.0f, 1e-4);
  EXPECT_NEAR(back.y, 0.0f, 1e-4);
  EXPECT_NEAR(back.z, 256.0f, 1e-4);
}

TEST(Volume, RejectsNonsenseDimensions) {
  EXPECT_THROW(Volume({0, 8, 8}), std::invalid_argument);
}

}  // namespace
}  // namespace cb

namespace cb {
namespace {

TEST(Volume, EveryConstructionAndAssignmentHasItsOwnInstanceId) {
  Volume a({4, 4, 4});
  Volume b({4, 4, 4});
  EXPECT_NE(a.instanceId(), b.instanceId());
  Volume c(a);
  EXPECT_NE(c.instanceId(), a.instanceId());
  uint64_t before = b.instanceId();
  b = Volume({4, 4, 4});
  EXPECT_NE(b.instanceId(), before) << "a volume assigned into the same address is a new volume";
  b = a;
  EXPECT_NE(b.instanceId(), a.instanceId());
  EXPECT_EQ(b.generation(), a.generation());
}

}  // namespace
}  // namespace cb
