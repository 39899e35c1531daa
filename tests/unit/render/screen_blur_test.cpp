// The paper styles' screen-space Gaussian (app/render/screen_blur.h): its weights, and the
// compose pass's reduced-scale still frame. At full scale (CB_FULL_SCALE) the compose pass fetches
// texels, guarded pixel by pixel by render_style_test's CPU reference; a still frame cast at a
// reduced scale (the attract loop's) reads the blurred image through bilinear taps, a program
// variant no other test draws: checked here to draw every pixel and its image-space outline.
#include "app/render/screen_blur.h"

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

// Pixels darker than mid grey: the outline and the darkest washes or hatching.
long darkPixels(const ImageRgba8& image) {
  long n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      n += image.at(x, y)[0] + image.at(x, y)[1] + image.at(x, y)[2] < 3 * 128;
  return n;
}

// The image-space outline (4A(1 − A) of the blurred coverage A) adds dark pixels to the unblurred
// moving frame of the same scale: measured +38 % (ink) and +39 % (sketch) at 240×160; without
// the blur's taps (A the unblurred coverage, 0 or 1 on a hit) it adds none. Weights that did
// not sum to 1 would leave A away from 1 inside the cloud and draw the outline over its whole
// area: measured 1.26× the full-scale still frame's dark pixels, so 2× bounds it.
constexpr double kMinOutlineGain = 1.15, kMaxDarkVsFullScale = 2.0;

TEST(ScreenBlur, AReducedScaleStillFrameDrawsTheBlurredOutline) {
  CB_REQUIRE_GL();
  constexpr int kW = 240, kH = 160;
  const Volume volume = makeBundledCumulus(glm::ivec3(32), 1);
  VolumeRenderer renderer;
  std::string err;
  ASSERT_TRUE(renderer.init(&err)) << err;
  renderer.sync(volume, Light{});
  Camera camera = Camera::reference();
  camera.fov_y_deg = 30.0f;  // the cloud fills the frame
  RenderTarget target;
  ASSERT_TRUE(target.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
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

}  // namespace
}  // namespace cb
