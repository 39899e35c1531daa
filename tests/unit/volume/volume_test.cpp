#include "app/volume/volume.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "app/core/parallel_for.h"

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

// The sparse sky: bricks exist only where something non-zero was written.
namespace cb {
namespace {

TEST(VolumeBricks, AllocatesOnlyTheBricksWrittenWithDensity) {
  Volume v({64, 64, 64});
  EXPECT_EQ(v.allocatedBricks(), 0u);
  EXPECT_FALSE(v.maxMerge(5, 5, 5, 0.0f)) << "merging zero raises nothing";
  const std::vector<float> zeros(64, 0.0f);
  v.writeLine({0, 3, 3}, 0, 64, zeros.data());
  v.set(40, 40, 40, 0.0f);
  EXPECT_EQ(v.allocatedBricks(), 0u) << "zeros written into empty bricks allocate nothing";
  EXPECT_TRUE(v.maxMerge(5, 5, 5, 0.25f));
  EXPECT_EQ(v.allocatedBricks(), 1u);
  EXPECT_NE(v.brick({0, 0, 0}), nullptr);
  // A line across a brick boundary allocates the two bricks it holds density in, not the
  // third it crosses with zeros.
  std::vector<float> line(40, 0.0f);
  line[10] = 1.0f;  // x = 14: brick 0
  line[20] = 1.0f;  // x = 24: brick 1
  v.writeLine({4, 20, 0}, 0, 40, line.data());
  EXPECT_EQ(v.allocatedBricks(), 3u);
  EXPECT_NE(v.brick({0, 1, 0}), nullptr);
  EXPECT_NE(v.brick({1, 1, 0}), nullptr);
  EXPECT_EQ(v.brick({2, 1, 0}), nullptr);
  EXPECT_EQ(v.memoryBytes(), 3 * Volume::kBrickBytes + v.brickCount() * 16);
  const std::vector<glm::ivec3> expected{{0, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  EXPECT_EQ(v.allocatedBrickList(), expected);
}

TEST(VolumeBricks, UnallocatedBricksReadZeroAndLinesCrossThem) {
  Volume v({40, 40, 40});
  v.set(17, 3, 30, 0.5f);
  v.set(17, 3, 31, -0.0f);  // a negative zero keeps its bits
  EXPECT_EQ(v.at(0, 0, 0), 0.0f);
  EXPECT_EQ(v.at(39, 39, 39), 0.0f);
  std::vector<float> z(40, 7.0f);
  v.readLine({17, 3, 0}, 2, 40, z.data());
  for (int i = 0; i < 40; ++i) {
    if (i == 30) continue;
    EXPECT_EQ(std::bit_cast<uint32_t>(z[size_t(i)]), i == 31 ? 0x80000000u : 0u) << i;
  }
  EXPECT_EQ(z[30], 0.5f);
  std::vector<float> y(40, 7.0f);
  v.readLine({17, 0, 30}, 1, 40, y.data());
  EXPECT_EQ(y[3], 0.5f);
  EXPECT_EQ(y[4], 0.0f);
  const std::vector<float> dense = v.toDense();
  EXPECT_EQ(dense[v.index(17, 3, 30)], 0.5f);
  EXPECT_TRUE(std::signbit(dense[v.index(17, 3, 31)]));
  Volume w({40, 40, 40});
  w.assignDense(dense.data());
  EXPECT_EQ(w.allocatedBricks(), v.allocatedBricks());
  EXPECT_EQ(0, std::memcmp(w.toDense().data(), dense.data(), dense.size() * sizeof(float)));
}

TEST(VolumeBricks, EmptyBricksAreReleasedAndFillZeroFreesAll) {
  Volume v({32, 32, 32});
  v.set(1, 1, 1, 1.0f);
  v.set(20, 1, 1, 1.0f);
  EXPECT_FALSE(v.releaseEmptyBrick({0, 0, 0})) << "it holds density";
  v.set(1, 1, 1, 0.0f);
  EXPECT_TRUE(v.releaseEmptyBrick({0, 0, 0}));
  EXPECT_EQ(v.allocatedBricks(), 1u);
  v.fill(0.5f);
  EXPECT_EQ(v.allocatedBricks(), 8u);
  EXPECT_EQ(v.at(31, 31, 31), 0.5f);
  v.fill(0.0f);
  EXPECT_EQ(v.allocatedBricks(), 0u);
  EXPECT_FALSE(v.hasDensity());
}

TEST(VolumeBricks, CopiesAreDeepAndMovesKeepTheBricks) {
  Volume a({32, 32, 32});
  a.set(3, 4, 5, 0.75f);
  Volume b = a;
  b.set(3, 4, 5, 0.25f);
  EXPECT_EQ(a.at(3, 4, 5), 0.75f);
  Volume c = std::move(b);
  EXPECT_EQ(c.at(3, 4, 5), 0.25f);
  EXPECT_EQ(c.allocatedBricks(), 1u);
}

TEST(VolumeBricks, ChangedBricksAreExactAtAnyAge) {
  Volume v({64, 64, 64});
  const uint64_t g0 = v.generation();
  v.set(1, 1, 1, 1.0f);
  v.set(50, 50, 50, 1.0f);
  const uint64_t g1 = v.generation();
  // Far more changes than the dirty-box history keeps, all in one brick.
  for (int i = 0; i < 1000; ++i) v.set(i % 16, 20, 20, float(i));
  const std::vector<glm::ivec3> since_g1{{0, 1, 1}};
  EXPECT_EQ(v.changedBricksSince(g1), since_g1);
  EXPECT_EQ(v.dirtySince(g1), v.bounds()) << "the boxes were forgotten; the bricks were not";
  const std::vector<glm::ivec3> since_g0{{0, 0, 0}, {0, 1, 1}, {3, 3, 3}};
  EXPECT_EQ(v.changedBricksSince(g0), since_g0);
  EXPECT_TRUE(v.changedBricksSince(v.generation()).empty());
}

TEST(VolumeBricks, ConcurrentWritersGiveTheSameBytesOnOneTwoAndEightThreads) {
  // Many threads raising voxels of shared bricks at once (as mapping's z slabs do): the bricks
  // are allocated once each and the bytes do not depend on the thread count.
  std::vector<std::vector<float>> results;
  std::vector<size_t> bricks;
  for (int threads : {1, 2, 8}) {
    setWorkerThreads(threads);
    Volume v({96, 64, 96});
    parallelFor(96, 1, [&](size_t, size_t z0, size_t z1) {
      for (int z = int(z0); z < int(z1); ++z)
        for (int y = 0; y < 64; ++y)
          for (int x = 0; x < 96; ++x) {
            const float r = glm::length(glm::vec3(x - 48, y - 32, z - 48));
            if (r < 30.0f) v.maxMerge(x, y, z, 1.0f - r / 30.0f + 0.001f * float((x * 7 + z) % 5));
          }
    });
    results.push_back(v.toDense());
    bricks.push_back(v.allocatedBricks());
  }
  setWorkerThreads(0);
  for (size_t i = 1; i < results.size(); ++i) {
    EXPECT_EQ(0, std::memcmp(results[0].data(), results[i].data(), results[0].size() * 4)) << i;
    EXPECT_EQ(bricks[0], bricks[i]);
  }
  EXPECT_GT(bricks[0], 0u);
  EXPECT_LT(bricks[0], size_t(6 * 4 * 6)) << "the corners of the grid hold no density";
}

TEST(VolumeBricks, AnEmptySkyOf1024x256x1024CostsOnlyItsBrickTable) {
  const glm::vec3 half(4.0f, 1.0f, 4.0f);  // today's voxel size: 2/256 world units
  Volume sky({1024, 256, 1024}, -half, half);
  EXPECT_EQ(sky.voxelSize(), Volume().voxelSize());
  EXPECT_EQ(sky.brickCount(), size_t(64 * 16 * 64));
  EXPECT_EQ(sky.allocatedBricks(), 0u);
  // 8 bytes of pointer and 8 of generation per brick: 1 MiB, against 1 GiB dense.
  EXPECT_EQ(sky.memoryBytes(), size_t(1) << 20);
  EXPECT_LE(sky.memoryBytes(), size_t(50) << 20);
  sky.set(1000, 200, 1000, 1.0f);
  EXPECT_EQ(sky.memoryBytes(), (size_t(1) << 20) + Volume::kBrickBytes);
  EXPECT_EQ(sky.at(1000, 200, 1000), 1.0f);
  EXPECT_EQ(sky.at(999, 200, 1000), 0.0f);
}

}  // namespace
}  // namespace cb
