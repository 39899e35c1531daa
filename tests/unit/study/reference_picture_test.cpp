// Every bundled protocol's reference pictures, as a participant sees them, have visible
// content: a picture whose shape is only in its alpha channel (the duck toy) is composited
// over the background, not shown as a blank box.
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "app/render/image_io.h"
#include "app/study/protocol.h"
#include "app/study/reference_picture.h"

namespace cb {
namespace {

// Standard deviation of the luminance (Rec. 709 weights), in 8-bit levels.
double luminanceSpread(const ImageRgba8& image) {
  double sum = 0, sum2 = 0;
  const size_t n = image.pixels.size() / 4;
  for (size_t i = 0; i < n; ++i) {
    const uint8_t* p = &image.pixels[4 * i];
    const double y = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    sum += y, sum2 += y * y;
  }
  const double mean = sum / double(n);
  return std::sqrt(std::max(0.0, sum2 / double(n) - mean * mean));
}

// A blank box has spread 0; 8 of 255 levels (3%) is a contrast anyone sees on a kiosk screen.
constexpr double kVisibleSpread = 8.0;

TEST(ReferencePicture, EveryBundledPictureHasVisibleContentAsShown) {
  const std::filesystem::path dir = std::filesystem::path(CB_SOURCE_DIR) / "config/study";
  int pictures = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".toml") continue;
    const StudyProtocol protocol = loadStudyProtocol(entry.path().string());
    for (const StudyTask& task : protocol.tasks) {
      if (task.image.empty()) continue;
      ++pictures;
      const ImageRgba8 shown = referencePictureForDisplay(readPng(task.image));
      EXPECT_GE(luminanceSpread(shown), kVisibleSpread) << task.image << " looks blank";
      for (size_t i = 3; i < shown.pixels.size(); i += 4) ASSERT_EQ(shown.pixels[i], 255);
    }
  }
  EXPECT_GE(pictures, 4) << "the bundled thesis protocol names four pictures";
}

// The check above would have caught the blank box: the duck's colour channels alone (what a
// copy of RGB showed) have no visible content.
TEST(ReferencePicture, TheDucksColourChannelsAloneAreBlank) {
  ImageRgba8 rgb_only =
      readPng(std::string(CB_SOURCE_DIR) + "/config/study/images/cloud1_duck.png");
  for (size_t i = 3; i < rgb_only.pixels.size(); i += 4) rgb_only.pixels[i] = 255;
  EXPECT_LT(luminanceSpread(rgb_only), kVisibleSpread);
}

TEST(ReferencePicture, CompositesAlphaOverTheBackground) {
  ImageRgba8 p;
  p.width = 3, p.height = 1;
  p.pixels = {100, 100, 100, 255, 100, 100, 100, 0, 0, 0, 0, 128};
  const ImageRgba8 shown = referencePictureForDisplay(p, {200, 200, 200});
  EXPECT_EQ(shown.pixels[0], 100);  // opaque: the picture's colour
  EXPECT_EQ(shown.pixels[4], 200);  // transparent: the background
  EXPECT_EQ(shown.pixels[8], 100);  // half: (0·128 + 200·127) / 255 = 99.6
}

}  // namespace
}  // namespace cb
