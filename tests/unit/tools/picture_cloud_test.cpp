// Picture → cloud: seen from the placing camera, the cloud's silhouette is the picture's; bad
// pictures get named errors and leave the volume untouched; same input ⇒ same bytes.
#include "app/tools/picture_cloud.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "app/core/parallel_for.h"
#include "app/render/image_io.h"
#include "app/tools/tool_error.h"
#include "tests/unit/mapping/opacity_projection.h"
#include "tests/unit/tools/tool_test_shapes.h"

namespace cb {
namespace {

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("cb_picture_cloud_" + name)).string();
}

std::string writeSilhouette(int w, int h) {
  ImageRgba8 image;
  image.width = w;
  image.height = h;
  image.pixels = test::cloudSilhouetteRgba(w, h);
  const std::string path = tempPath("silhouette.png");
  writePng(path, image);
  return path;
}

ToolView smallView() {
  ToolView view;
  view.camera = Camera::reference();
  view.view_width = 320;
  view.view_height = 180;
  view.size_fraction = 0.6f;
  return view;
}

TEST(PictureCloud, SilhouetteFromThePlacingCameraMatchesThePicture) {
  const int pw = 256, ph = 192;
  const std::string path = writeSilhouette(pw, ph);
  for (float orbit : {0.0f, 70.0f}) {
    Volume volume(glm::ivec3(128));
    ToolView view = smallView();
    view.camera = view.camera.orbited(orbit);
    const uint64_t before = volume.generation();
    const VoxelBox box = pictureToCloud(path, view, PictureCloudParams{}, &volume);
    ASSERT_FALSE(box.empty());
    EXPECT_EQ(volume.dirtySince(before), box);

    const std::vector<float> opacity =
        test::projectOpacity(volume, view.camera, view.view_width, view.view_height);
    const ShapeMask mask = shapeMaskFromRgba(pw, ph, test::cloudSilhouetteRgba(pw, ph));
    const PicturePlacement placement(view, volume, pw, ph);
    long long both = 0, either = 0;
    for (int y = 0; y < view.view_height; ++y)
      for (int x = 0; x < view.view_width; ++x) {
        const glm::vec2 pic =
            (glm::vec2(x + 0.5f, y + 0.5f) - placement.toView({0, 0})) / placement.scale();
        const int px = int(std::floor(pic.x)), py = int(std::floor(pic.y));
        const bool want = px >= 0 && py >= 0 && px < pw && py < ph && mask.at(px, py);
        const bool have = opacity[size_t(y) * view.view_width + x] > 0.3f;
        both += want && have;
        either += want || have;
      }
    ASSERT_GT(either, 0);
    const double iou = double(both) / double(either);
    EXPECT_GE(iou, 0.85) << "orbit " << orbit;
    std::printf("orbit %.0f: IoU %.3f\n", orbit, iou);
  }
}

TEST(PictureCloud, SameInputGivesTheSameBytesOnAnyThreadCount) {
  const std::string path = writeSilhouette(128, 96);
  std::vector<float> first;
  for (int threads : {1, 2, 8}) {
    setWorkerThreads(threads);
    Volume volume(glm::ivec3(96));
    pictureToCloud(path, smallView(), PictureCloudParams{}, &volume);
    std::vector<float> bytes = volume.toDense();
    if (first.empty())
      first = bytes;
    else
      EXPECT_EQ(bytes, first) << threads << " threads";
  }
  setWorkerThreads(0);
}

void expectRefused(const std::string& path, ToolErrorKind kind) {
  Volume volume(glm::ivec3(32));
  volume.set(3, 4, 5, 0.25f);
  const uint64_t generation = volume.generation();
  try {
    pictureToCloud(path, smallView(), PictureCloudParams{}, &volume);
    ADD_FAILURE() << path << " was accepted";
  } catch (const ToolError& e) {
    EXPECT_EQ(e.kind, kind) << e.what();
  }
  EXPECT_EQ(volume.generation(), generation);
  double sum = 0;
  {
    const std::vector<float> volume_dense = volume.toDense();
    for (size_t i = 0; i < volume.voxelCount(); ++i) sum += volume_dense[i];
  }
  EXPECT_EQ(sum, 0.25);
}

TEST(PictureCloud, BadPicturesAreRefusedByNameAndLeaveTheVolumeUntouched) {
  const std::string zero = tempPath("zero.png");
  test::writePngHeaderOnly(zero, 0, 64);
  expectRefused(zero, ToolErrorKind::kEmptyImage);

  const std::string huge = tempPath("huge.png");
  test::writePngHeaderOnly(huge, 100000, 100000);  // decoding it would need 40 GB
  expectRefused(huge, ToolErrorKind::kImageTooLarge);

  ImageRgba8 blank;
  blank.width = blank.height = 32;
  blank.pixels.assign(32 * 32 * 4, 255);
  const std::string blank_path = tempPath("blank.png");
  writePng(blank_path, blank);
  expectRefused(blank_path, ToolErrorKind::kEmptyImage);

  const std::string text = tempPath("not_a_png.png");
  std::ofstream(text) << "P3\n2 2\n255\n0 0 0 1 1 1 2 2 2 3 3 3\n";
  expectRefused(text, ToolErrorKind::kNotPng);

  expectRefused(tempPath("does_not_exist.png"), ToolErrorKind::kUnreadableFile);
}

}  // namespace
}  // namespace cb
