// The paper styles' screen-space Gaussian (app/render/screen_blur.h): its weights, and the
// compose pass's reduced-scale still frame. At full scale (CB_FULL_SCALE) the compose pass fetches
// texels, guarded pixel by pixel by render_style_test's CPU reference; a still frame cast at a
// reduced scale (the attract loop's) reads the blurred image through bilinear taps, a program
// variant no other test draws: checked here to draw every pixel and its image-space outline.
// And the blur confined to the boundary's projection (FramePlan::blur_rect) changes no pixel.
#include "app/render/screen_blur.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "app/render/render_style.h"
#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"
#include "app/volume/scene_generators.h"
#include "tests/unit/render/gl_test_context.h"

namespace cb {
namespace {

TEST(ScreenBlur, WeightsAreTheNormalisedGaussianWithinTheRadius) {
  for (float sigma : {kSketchOutlineSigma, 1.4142f, 1.8f}) {
    const int radius = inkBleedRadius(sigma);
    const ScreenBlurWeights w = screenBlurWeights(sigma, radius);
    float total = w[0];
    for (int i = 1; i <= radius; ++i) {
      total += 2.0f * w[i];
      // e^(−i²/(2σ²)) relative to the centre, to float precision
      EXPECT_NEAR(w[i] / w[0], std::exp(-float(i * i) / (2.0f * sigma * sigma)), 1e-6f)
          << "sigma " << sigma << " tap " << i;
    }
    EXPECT_NEAR(total, 1.0f, 1e-6f) << "sigma " << sigma;
    for (int i = radius + 1; i <= kMaxInkBleedRadius; ++i) EXPECT_EQ(w[i], 0.0f);
  }
  EXPECT_EQ(screenBlurDefine(2), "#define CB_BLUR_RADIUS 2\n");
}

// Channel sum of |a − b| at pixel (x, y).
int pixelDifference(const ImageRgba8& a, const ImageRgba8& b, int x, int y) {
  int d = 0;
  for (int c = 0; c < 3; ++c) d += std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c]));
  return d;
}

// Pixels darker than mid grey: the outline and the darkest washes or hatching.
long darkPixels(const ImageRgba8& image) {
  long n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      n += image.at(x, y)[0] + image.at(x, y)[1] + image.at(x, y)[2] < 3 * 128;
  return n;
}

// The frames below: the 32³ cumulus synced under the default light, a 240×160 RGBA8 target.
class ScreenBlurFrame : public ::testing::Test {
 protected:
  static constexpr int kW = 240, kH = 160;
  void SetUp() override {
    CB_REQUIRE_GL();
    ASSERT_TRUE(renderer.init(&err)) << err;
    renderer.sync(volume, Light{});
    ASSERT_TRUE(target.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  }
  const Volume volume = makeBundledCumulus(glm::ivec3(32), 1);
  VolumeRenderer renderer;
  RenderTarget target;
  std::string err;
};

// The image-space outline (4A(1 − A) of the blurred coverage A) adds dark pixels to the unblurred
// moving frame of the same scale: measured +38 % (ink) and +39 % (sketch) at 240×160; without
// the blur's taps (A the unblurred coverage, 0 or 1 on a hit) it adds none. Weights that did
// not sum to 1 would leave A away from 1 inside the cloud and draw the outline over its whole
// area: measured 1.26× the full-scale still frame's dark pixels, so 2× bounds it.
constexpr double kMinOutlineGain = 1.15, kMaxDarkVsFullScale = 2.0;

TEST_F(ScreenBlurFrame, AReducedScaleStillFrameDrawsTheBlurredOutline) {
  Camera camera = Camera::reference();
  camera.fov_y_deg = 30.0f;                            // the cloud fills the frame
  const float sentinel[4] = {1.0f, 0.0f, 1.0f, 1.0f};  // magenta: a pixel the pass did not draw
  for (RenderStyle style : {RenderStyle::kInk, RenderStyle::kSketch}) {
    RenderOptions options;
    options.style = style;
    auto frame = [&](float scale, bool moving) {
      options.scale = scale;
      options.moving = moving;
      glClearNamedFramebufferfv(target.fbo(), GL_COLOR, 0, sentinel);
      renderer.render(camera, kW, kH, target.fbo(), options);
      return target.readRgba8();
    };
    const ImageRgba8 full = frame(1.0f, false);
    const ImageRgba8 still = frame(0.5f, false);  // blurred at half scale, bilinear taps
    const ImageRgba8 moving = frame(0.5f, true);  // the same scale, not blurred
    long undrawn = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x)
        undrawn += still.at(x, y)[0] == 255 && still.at(x, y)[1] == 0 && still.at(x, y)[2] == 255;
    const long dark_full = darkPixels(full), dark_still = darkPixels(still),
               dark_moving = darkPixels(moving);
    std::printf(
        "%s: dark pixels full-scale still %ld, half-scale still %ld, half-scale moving %ld; "
        "%ld pixels undrawn\n",
        renderStyleName(style), dark_full, dark_still, dark_moving, undrawn);
    EXPECT_EQ(undrawn, 0) << renderStyleName(style);
    EXPECT_GT(double(dark_still), kMinOutlineGain * double(dark_moving)) << renderStyleName(style);
    EXPECT_LT(double(dark_still), kMaxDarkVsFullScale * double(dark_full))
        << renderStyleName(style);
  }
}

// The blur runs only within its reach of the boundary's projection (FramePlan::blur_rect), the
// rest drawn by the compose pass's unblurred variant: the frame must equal one cast without
// skipping (every pixel cast and blurred), here with the cloud in a corner of the frame so that
// most of it lies outside the rectangle; on bare paper and over the sky (CB_OVER_SKY).
TEST_F(ScreenBlurFrame, BlurringOnlyNearTheBoundaryChangesNoPixel) {
  Camera camera = Camera::reference();
  camera.fov_y_deg = 70.0f;                      // the cloud small in the frame
  camera.target += glm::vec3(0.6f, 0.3f, 0.0f);  // and off centre
  for (RenderStyle style : {RenderStyle::kInk, RenderStyle::kSketch})
    for (bool over_sky : {false, true}) {
      RenderOptions options;
      options.style = style;
      if (over_sky) {  // the paper only inside the cloud, over the sky drawn first
        options.sky.kind = SkyKind::kColour;
        options.style_params.ink.sky = options.style_params.sketch.sky = true;
      }
      auto frame = [&](bool skip) {
        options.skip_empty_space = skip;
        renderer.render(camera, kW, kH, target.fbo(), options);
        return target.readRgba8();
      };
      const ImageRgba8 skipped = frame(true), whole = frame(false);
      const ImageRgba8 paper = [&] {
        VolumeRenderer empty;
        std::string e;
        EXPECT_TRUE(empty.init(&e)) << e;
        empty.sync(Volume(glm::ivec3(32)), Light{});
        options.skip_empty_space = true;
        empty.render(camera, kW, kH, target.fbo(), options);
        return target.readRgba8();
      }();
      long cloud = 0, differ = 0;
      int worst = 0;
      for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
          cloud += pixelDifference(whole, paper, x, y) > 0;
          const int d = pixelDifference(skipped, whole, x, y);
          differ += d > 0;
          worst = std::max(worst, d);
        }
      std::printf(
          "%s%s: %ld of %d pixels differ from the empty frame; skipping vs not: %ld differ, "
          "worst %d (channel sum)\n",
          renderStyleName(style), over_sky ? " over the sky" : "", cloud, kW * kH, differ, worst);
      EXPECT_GT(cloud, 500) << renderStyleName(style) << ": the cloud is in view";
      EXPECT_LT(cloud, kW * kH / 3) << renderStyleName(style) << ": most of the frame is paper";
      EXPECT_EQ(worst, 0) << renderStyleName(style);
    }
}

}  // namespace
}  // namespace cb
