#include "app/render/occupancy_pyramid.h"

#include <gtest/gtest.h>

#include "app/volume/scene_generators.h"

namespace cb {
namespace {

// The definition, straight: a level-0 cell is occupied iff a non-zero voxel lies in its brick
// dilated by one voxel.
uint8_t expectedCell(const Volume& v, int brick, glm::ivec3 c) {
  for (int z = c.z * brick - 1; z <= c.z * brick + brick; ++z)
    for (int y = c.y * brick - 1; y <= c.y * brick + brick; ++y)
      for (int x = c.x * brick - 1; x <= c.x * brick + brick; ++x)
        if (VoxelBox{glm::ivec3(0), v.dims()}.contains({x, y, z}) && v.at(x, y, z) != 0.0f)
          return 1;
  return 0;
}

void expectConsistent(const OccupancyPyramid& p, const Volume& v) {
  glm::ivec3 d0 = p.level_dims[0];
  for (int z = 0; z < d0.z; ++z)
    for (int y = 0; y < d0.y; ++y)
      for (int x = 0; x < d0.x; ++x)
        ASSERT_EQ(p.at(0, {x, y, z}), expectedCell(v, p.brick, {x, y, z}))
            << x << "," << y << "," << z;
  for (int m = 1; m < p.levelCount(); ++m) {
    glm::ivec3 d = p.level_dims[size_t(m)];
    for (int z = 0; z < d.z; ++z)
      for (int y = 0; y < d.y; ++y)
        for (int x = 0; x < d.x; ++x) {
          uint8_t any = 0;
          for (int k = 0; k < 8; ++k) {
            glm::ivec3 c = glm::ivec3(x, y, z) * 2 + glm::ivec3(k & 1, (k >> 1) & 1, k >> 2);
            glm::ivec3 dc = p.level_dims[size_t(m - 1)];
            if (c.x < dc.x && c.y < dc.y && c.z < dc.z) any |= p.at(m - 1, c);
          }
          ASSERT_EQ(p.at(m, {x, y, z}), any) << "level " << m;
        }
  }
  EXPECT_EQ(p.level_dims.back(), glm::ivec3(1));
}

TEST(OccupancyPyramid, SingleVoxelMarksEveryCellWhoseDilatedBrickHoldsIt) {
  // Voxel 4 sits on a brick boundary: cells 0 (dilated to voxel 4) and 1 both see it.
  Volume v = makeSingleVoxel(glm::ivec3(16), {4, 7, 11});
  OccupancyPyramid p = buildOccupancy(v);
  EXPECT_EQ(p.at(0, {0, 1, 2}), 1);
  EXPECT_EQ(p.at(0, {1, 1, 2}), 1);
  EXPECT_EQ(p.at(0, {1, 1, 3}), 1);  // voxel 11 is next to brick 3 (12..15)
  EXPECT_EQ(p.at(0, {2, 1, 2}), 0);
  expectConsistent(p, v);
  EXPECT_EQ(p.at(p.levelCount() - 1, {0, 0, 0}), 1);
}

TEST(OccupancyPyramid, NonPowerOfTwoDimsArePaddedAndConsistent) {
  Volume v = makeSparsePuffs({37, 20, 45}, 3);
  OccupancyPyramid p = buildOccupancy(v);
  EXPECT_EQ(p.level_dims[0], glm::ivec3(16, 8, 16));
  expectConsistent(p, v);
}

TEST(OccupancyPyramid, DirtyUpdateEqualsARebuild) {
  Volume v = makeSparsePuffs(glm::ivec3(48), 4);
  OccupancyPyramid p = buildOccupancy(v);
  // Add a voxel, then clear a puff region: both kinds of change must be followed.
  v.set(40, 2, 9, 0.5f);
  VoxelBox cleared{{10, 10, 10}, {30, 30, 30}};
  for (int z = 10; z < 30; ++z)
    for (int y = 10; y < 30; ++y)
      for (int x = 10; x < 30; ++x) v.voxelForWrite(x, y, z) = 0.0f;
  v.markDirty(cleared);
  VoxelBox cells = updateOccupancy(p, v, v.dirtySince(1));
  EXPECT_FALSE(cells.empty());
  expectConsistent(p, v);
  OccupancyPyramid rebuilt = buildOccupancy(v);
  EXPECT_EQ(p.levels, rebuilt.levels);
}

}  // namespace
}  // namespace cb
