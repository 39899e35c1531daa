// The sky's extent (app/volume/sky_extent.h): the home box at the centre of a wider sky at the
// same voxel size, and clouds of the one-box sky placed into it where they were in the world.
#include <cmath>
#include <filesystem>

#include <unistd.h>

#include <gtest/gtest.h>

#include "app/volume/scene_generators.h"
#include "app/volume/sky_extent.h"
#include "app/volume/volume_file.h"

namespace cb {
namespace {

TEST(SkyExtent, DefaultIsAThousandVoxelsWideAtTheOldVoxelSize) {
  const SkyExtent sky{256, kDefaultSkySpan};
  EXPECT_EQ(sky.dims(), glm::ivec3(1024, 256, 1024));
  const Volume v = makeSkyVolume(sky);
  EXPECT_EQ(v.voxelSize(), Volume(glm::ivec3(256)).voxelSize());  // the thesis box's voxels
  EXPECT_EQ(v.allocatedBricks(), 0u);
  EXPECT_LT(v.memoryBytes(), size_t(2) << 20);  // the brick table only
  // The home box's voxels are the old box's: world [-1,1]³.
  EXPECT_EQ(v.voxelToWorld(glm::vec3(sky.homeOffset())), glm::vec3(-1.0f));
  EXPECT_EQ(v.voxelToWorld(glm::vec3(sky.homeOffset() + glm::ivec3(256))), glm::vec3(1.0f));
}

TEST(SkyExtent, RefusesExtentsItCannotMake) {
  EXPECT_EQ(SkyExtent({256, 1}).check(), "");
  EXPECT_NE(SkyExtent({256, 0}).check(), "");
  EXPECT_NE(SkyExtent({256, 9}).check(), "");
  EXPECT_NE(SkyExtent({512, 8}).check().find("2048"), std::string::npos);
  EXPECT_NE(SkyExtent({255, 2}).check().find("odd grid"), std::string::npos);
  EXPECT_THROW(makeSkyVolume({512, 8}), std::invalid_argument);
}

TEST(SkyExtent, PlacesAHomeBoxCloudWhereItWasInTheWorld) {
  const Volume home = makeBundledCumulus(glm::ivec3(32), 1);
  const SkyExtent sky{32, 4};
  ASSERT_TRUE(isHomeBoxCloud(home, sky));
  const Volume placed = placeInSky(home, sky);
  EXPECT_EQ(placed.dims(), glm::ivec3(128, 32, 128));
  const glm::ivec3 o = sky.homeOffset();
  EXPECT_EQ(o, glm::ivec3(48, 0, 48));
  size_t nonzero = 0;
  for (int z = 0; z < 32; ++z)
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x) {
        ASSERT_EQ(placed.at(o.x + x, y, o.z + z), home.at(x, y, z));
        nonzero += home.at(x, y, z) != 0.0f;
      }
  ASSERT_GT(nonzero, 0u);
  // Nothing outside the home box.
  for (const glm::ivec3& b : placed.allocatedBrickList()) {
    const VoxelBox box = placed.brickBox(b);
    EXPECT_TRUE(box.intersect({o, o + glm::ivec3(32)}) == box);
  }
  // A world point names the same density in both.
  const glm::vec3 w(0.1f, -0.2f, 0.05f);
  const glm::ivec3 in_home(home.worldToVoxel(w)), in_sky(placed.worldToVoxel(w));
  EXPECT_EQ(home.at(in_home.x, in_home.y, in_home.z), placed.at(in_sky.x, in_sky.y, in_sky.z));
  // One box: the cloud as it is.
  const Volume same = placeInSky(home, {32, 1});
  EXPECT_EQ(same.dims(), home.dims());
  EXPECT_EQ(same.at(16, 8, 16), home.at(16, 8, 16));
  EXPECT_THROW(placeInSky(home, {64, 4}), std::invalid_argument);
}

TEST(SkyExtent, RecognisesSkies) {
  const std::optional<SkyExtent> sky = skyExtentOf(makeSkyVolume({64, 3}));
  ASSERT_TRUE(sky.has_value());
  EXPECT_EQ(sky->grid, 64);
  EXPECT_EQ(sky->span, 3);
  const std::optional<SkyExtent> box = skyExtentOf(Volume(glm::ivec3(48)));
  ASSERT_TRUE(box.has_value());
  EXPECT_EQ(box->span, 1);
  EXPECT_FALSE(skyExtentOf(Volume(glm::ivec3(64, 32, 64))).has_value());  // [-1,1]³, not a sky
  EXPECT_FALSE(isHomeBoxCloud(makeSkyVolume({64, 3}), {64, 3}));
}

TEST(SkyExtent, GrowsByWholeBricksKeepingEveryVoxelWhereItWasInTheWorld) {
  const SkyExtent from{64, 2}, to{64, 5};
  Volume sky = placeInSky(makeBundledCumulus(glm::ivec3(64), 1), from);
  sky.set(0, 3, 127, 0.25f);  // a voxel at the old sky's far corner
  const Volume before = sky;
  const size_t bricks = sky.allocatedBricks();
  ASSERT_GT(bricks, 0u);
  const glm::ivec3 offset = growthOffset(from, to);
  EXPECT_EQ(offset, glm::ivec3(96, 0, 96));
  const Volume grown = growSky(std::move(sky), from, to);
  EXPECT_EQ(grown.dims(), to.dims());
  EXPECT_EQ(grown.worldMin(), to.worldMin());
  EXPECT_EQ(skyExtentOf(grown)->span, 5);
  EXPECT_EQ(grown.allocatedBricks(), bricks);
  EXPECT_EQ(sky.allocatedBricks(), 0u);  // moved, not copied
  for (const glm::ivec3& b : before.allocatedBrickList()) {
    const VoxelBox box = before.brickBox(b);
    for (int z = box.lo.z; z < box.hi.z; ++z)
      for (int y = box.lo.y; y < box.hi.y; ++y)
        for (int x = box.lo.x; x < box.hi.x; ++x)
          ASSERT_EQ(grown.at(x + offset.x, y, z + offset.z), before.at(x, y, z));
  }
  // The same world point names the same voxel value.
  const glm::vec3 w(0.3f, 0.1f, -0.4f);
  const glm::ivec3 a(before.worldToVoxel(w)), b(grown.worldToVoxel(w));
  EXPECT_EQ(b, a + offset);
  // The home box stays on [-1,1]³.
  EXPECT_EQ(grown.voxelToWorld(glm::vec3(to.homeOffset())), glm::vec3(-1.0f));
  // The whole grown sky is marked changed (consumers start afresh).
  EXPECT_EQ(grown.dirtySince(0), grown.bounds());
  // A volume file carries the grown extent: it opens as the same sky, voxel for voxel.
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("cb_grown_sky_" + std::to_string(::getpid()) + ".cbvol"))
                               .string();
  saveVolume(grown, path);
  const Volume loaded = loadVolume(path);
  std::filesystem::remove(path);
  EXPECT_EQ(loaded.dims(), to.dims());
  EXPECT_EQ(loaded.worldMin(), to.worldMin());
  EXPECT_EQ(loaded.worldMax(), to.worldMax());
  for (const glm::ivec3& b : grown.allocatedBrickList()) {
    const VoxelBox box = grown.brickBox(b);
    for (int z = box.lo.z; z < box.hi.z; ++z)
      for (int y = box.lo.y; y < box.hi.y; ++y)
        for (int x = box.lo.x; x < box.hi.x; ++x) ASSERT_EQ(loaded.at(x, y, z), grown.at(x, y, z));
  }
}

TEST(SkyExtent, ChoosesTheNarrowestSkyHoldingAStrokeWithinTheLimits) {
  const SkyExtent sky{256, 4};
  EXPECT_EQ(widestSkySpan(256, 4, kMaxSkySpan), 8);
  EXPECT_EQ(widestSkySpan(512, 2, kMaxSkySpan), 4);  // 2048 voxels across at most
  EXPECT_EQ(widestSkySpan(48, 1, kMaxSkySpan), 1);   // a span step is not whole bricks
  EXPECT_EQ(widestSkySpan(256, 4, 4), 4);            // a fixed sky
  EXPECT_EQ(skyToHold(sky, 8, {-1.0f, -1.0f}, {3.9f, 1.0f}).span, 4);
  EXPECT_EQ(skyToHold(sky, 8, {-1.0f, -1.0f}, {4.1f, 1.0f}).span, 5);
  EXPECT_EQ(skyToHold(sky, 8, {-6.5f, -1.0f}, {0.0f, 1.0f}).span, 7);
  EXPECT_EQ(skyToHold(sky, 8, {-1.0f, -1.0f}, {30.0f, 1.0f}).span, 8);  // as wide as allowed
  EXPECT_EQ(skyToHold(sky, 6, {-1.0f, -1.0f}, {30.0f, 1.0f}).span, 6);
  EXPECT_EQ(skyToHold(sky, 8, {-1.0f, -1.0f}, {NAN, 1.0f}).span, 8);
  Volume narrow = makeSkyVolume({48, 1});
  EXPECT_THROW(growSky(std::move(narrow), {48, 1}, {48, 2}), std::invalid_argument);  // 24
  Volume four = makeSkyVolume(sky);
  EXPECT_THROW(growSky(std::move(four), sky, {256, 3}), std::invalid_argument);
}

}  // namespace
}  // namespace cb
