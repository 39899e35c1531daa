#include "app/volume/volume_erase.h"

#include <gtest/gtest.h>

namespace cb {
namespace {

TEST(VolumeErase, VacuumHolesTheCloudAndReleasesTheBricksItEmptied) {
  Volume v({64, 64, 64});
  v.fill(0.5f);
  ASSERT_EQ(v.allocatedBricks(), 64u);
  // Voxels are 1/32 world units: a sphere of radius 1.2 (38.4 voxels) whose rim fades over its
  // outer quarter empties every voxel within 28.8 voxels of the centre, which holds the eight
  // central bricks (their farthest voxel centres lie 15.5·√3 ≈ 26.8 voxels away) and no other.
  const VoxelBox changed = vacuumSphere(v, glm::vec3(0.0f), 1.2f);
  EXPECT_FALSE(changed.empty());
  EXPECT_EQ(v.at(32, 32, 32), 0.0f);
  EXPECT_EQ(v.at(0, 0, 0), 0.5f) << "nothing outside the sphere changed";
  EXPECT_EQ(v.allocatedBricks(), 64u - 8u);
  for (int b = 1; b <= 2; ++b) EXPECT_EQ(v.brick(glm::ivec3(b)), nullptr);
  // A vacuum over the whole sky leaves no brick.
  vacuumSphere(v, glm::vec3(0.0f), 4.0f);
  EXPECT_EQ(v.allocatedBricks(), 0u);
  EXPECT_FALSE(v.hasDensity());
}

}  // namespace
}  // namespace cb
