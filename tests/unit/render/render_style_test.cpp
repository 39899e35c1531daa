// Every render style's shader against an independent CPU evaluation of its formula
// (style_reference.h) on a grid of rays through a small cumulus: the GPU image must match the
// CPU's pixel by pixel within a tolerance (8-bit inputs, llvmpipe's filtering precision).
// Also: names round-trip, and the partial re-rendering rule of screen-space styles.
#include "app/render/render_style.h"

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"
#include "app/volume/scene_generators.h"
#include "tests/unit/render/gl_test_context.h"
#include "tests/unit/render/style_reference.h"

namespace cb {
namespace {

constexpr int kW = 120, kH = 80;

TEST(RenderStyle, NamesRoundTripAndUnknownNamesAreRejected) {
  for (RenderStyle s : kAllRenderStyles) EXPECT_EQ(parseRenderStyle(renderStyleName(s)), s);
  EXPECT_EQ(parseRenderStyle("Ink"), std::nullopt);
  EXPECT_EQ(parseRenderStyle(""), std::nullopt);
  EXPECT_EQ(renderStyleNameList(), "thesis|physical|ink|cartoon|sketch");
  EXPECT_EQ(RenderOptions{}.style, RenderStyle::kThesis);
  EXPECT_EQ(screenSpaceReach(RenderStyle::kInk), 3);
  EXPECT_EQ(screenSpaceReach(RenderStyle::kSketch), 2);  // its outline blur, σ = 0.85
  EXPECT_EQ(screenSpaceReach(RenderStyle::kThesis), 0);
}

TEST(RenderStyle, EveryStyleCompilesStillAndMoving) {
  CB_REQUIRE_GL();
  VolumeRenderer renderer;
  std::string err;
  ASSERT_TRUE(renderer.init(&err)) << err;
  for (RenderStyle style : kAllRenderStyles)
    for (bool moving : {false, true}) {
      RenderOptions options;
      options.style = style;
      options.moving = moving;
      EXPECT_TRUE(renderer.prepare(options, &err)) << renderStyleName(style) << ": " << err;
    }
}

struct ShaderCase {
  RenderStyle style;
  bool moving;
  int tolerance;       // of 255, any channel
  bool tuned = false;  // non-default style parameters (render_style_params.h), see tunedParams
};

// Parameters away from every default, so a parameter the shader ignored would show.
StyleParams tunedParams() {
  StyleParams p;
  p.physical.reflection = 0.4f;
  p.physical.scattering = 0.7f;
  p.physical.forward_g = 0.8f;
  p.physical.back_g = -0.1f;
  p.physical.forward_weight = 0.6f;
  p.physical.octaves = 2;
  p.physical.ambient = 0.8f;
  p.physical.exposure = 1.1f;
  p.physical.erosion = 0.3f;
  p.ink.wash = 0.6f;
  p.ink.line_width = 0.65f;
  p.ink.bleed_sigma = 1.8f;  // kernel radius 4 instead of 3
  p.cartoon.band_thresholds = glm::vec3(0.1f, 0.35f, 0.6f);
  p.cartoon.outline_width = 0.45f;
  p.sketch.outline_width = 0.45f;
  return p;
}
// On outline and silhouette ramps (ReferencePixel::sensitive) a few /255 of filtering
// difference in density become several /255 of colour; measured worst there: 13.
constexpr int kRampTolerance = 24;

class StyleShaderMatchesCpu : public ::testing::TestWithParam<ShaderCase> {};

TEST_P(StyleShaderMatchesCpu, OnAGridOfRays) {
  CB_REQUIRE_GL();
  const ShaderCase& c = GetParam();
  const Volume volume = makeBundledCumulus(glm::ivec3(32), 1);
  Light light;
  light.direction = Light::directionTowards(glm::vec3(-3.0f, 2.0f, 2.0f));
  light.colour = glm::vec3(1.0f, 0.9f, 0.8f);
  VolumeRenderer renderer;
  std::string err;
  ASSERT_TRUE(renderer.init(&err)) << err;
  renderer.sync(volume, light);
  RenderOptions options;
  options.style = c.style;
  options.moving = c.moving;
  if (c.tuned) options.style_params = tunedParams();
  options.skip_empty_space = false;  // the CPU marches every sample from the box entry
  RenderTarget target;
  ASSERT_TRUE(target.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  Camera camera = Camera::reference();
  camera.fov_y_deg = 30.0f;  // the cloud fills the frame
  renderer.render(camera, kW, kH, target.fbo(), options);
  const ImageRgba8 image = target.readRgba8();

  ReferenceScene scene;
  scene.dims = volume.dims();
  scene.world_min = volume.worldMin();
  scene.world_max = volume.worldMax();
  packDensityAndLight(volume, renderer.lightVolume(), volume.bounds(), &scene.voxels);
  scene.light = light;
  scene.camera = camera;
  scene.width = kW;
  scene.height = kH;
  scene.options = options;
  if (c.style == RenderStyle::kPhysical) scene.noise = makeDetailNoise();

  int compared = 0, skipped = 0, worst = 0, cloud_pixels = 0, on_ramps = 0, worst_on_ramps = 0;
  for (int y = 4; y < kH - 4; y += 5)
    for (int x = 4; x < kW - 4; x += 5) {
      ReferencePixel ref = referencePixel(scene, x, y);
      if (ref.ambiguous) {
        ++skipped;
        continue;
      }
      ++compared;
      const uint8_t* px = image.at(x, y);
      int pixel_worst = 0;
      for (int ch = 0; ch < 4; ++ch) {
        int expected = int(std::lround(std::clamp(ref.rgba[ch], 0.0f, 1.0f) * 255.0f));
        pixel_worst = std::max(pixel_worst, std::abs(int(px[ch]) - expected));
      }
      const int tolerance = ref.sensitive ? kRampTolerance : c.tolerance;
      on_ramps += ref.sensitive;
      (ref.sensitive ? worst_on_ramps : worst) =
          std::max(ref.sensitive ? worst_on_ramps : worst, pixel_worst);
      const uint8_t* corner = image.at(0, 0);
      if (std::abs(px[0] - corner[0]) + std::abs(px[1] - corner[1]) + std::abs(px[2] - corner[2]) >
          30)
        ++cloud_pixels;
      EXPECT_LE(pixel_worst, tolerance)
          << "pixel " << x << "," << y << ": GPU " << int(px[0]) << "," << int(px[1]) << ","
          << int(px[2]) << " CPU " << ref.rgba.r * 255 << "," << ref.rgba.g * 255 << ","
          << ref.rgba.b * 255;
    }
  std::printf(
      "%s%s%s: %d rays compared (%d on the cloud), %d near a threshold skipped; worst %d/255, "
      "%d on outline ramps (worst %d/255)\n",
      renderStyleName(c.style), c.moving ? " (moving)" : "", c.tuned ? " (tuned)" : "", compared,
      cloud_pixels, skipped, worst, on_ramps, worst_on_ramps);
  // The tuned ink bleeds over 9×9 pixels instead of 7×7, so more rays have a neighbour near a
  // band threshold and are skipped.
  const bool wide_kernel = c.tuned && c.style == RenderStyle::kInk;
  // The sketch's rays that just miss the surface add coverage but no grey of their own (its
  // outline is the compose pass's): 59 of the grid's rays differ from the paper where the
  // near-miss band's grey made it 60 and more.
  const int min_cloud = wide_kernel ? 45 : c.style == RenderStyle::kSketch ? 55 : 60;
  EXPECT_GE(compared, wide_kernel ? 160 : 200);  // most of the 22×14 grid
  EXPECT_GE(cloud_pixels, min_cloud);            // and many on the cloud, not the background
  EXPECT_GE(compared - on_ramps, wide_kernel ? 80 : 100);  // most held to the strict tolerance
}

INSTANTIATE_TEST_SUITE_P(AllStyles, StyleShaderMatchesCpu,
                         ::testing::Values(ShaderCase{RenderStyle::kThesis, false, 2},
                                           ShaderCase{RenderStyle::kPhysical, false, 3},
                                           ShaderCase{RenderStyle::kInk, false, 3},
                                           ShaderCase{RenderStyle::kInk, true, 3},
                                           ShaderCase{RenderStyle::kCartoon, false, 3},
                                           ShaderCase{RenderStyle::kSketch, false, 3},
                                           ShaderCase{RenderStyle::kPhysical, false, 3, true},
                                           ShaderCase{RenderStyle::kInk, false, 3, true},
                                           ShaderCase{RenderStyle::kCartoon, false, 3, true},
                                           ShaderCase{RenderStyle::kSketch, false, 3, true}),
                         [](const ::testing::TestParamInfo<ShaderCase>& info) {
                           return std::string(renderStyleName(info.param.style)) +
                                  (info.param.moving ? "_moving" : "") +
                                  (info.param.tuned ? "_tuned" : "");
                         });

// Partial re-rendering (RenderOptions::region): a frame of scene B, then only a rectangle R of
// scene A. Inside R the pixels must equal a full-frame render of A — for ink, whose bleeding
// reads 3 pixels around each pixel, only because R is cast dilated by that reach — and outside
// R the target must still hold B.
struct PartialCase {
  RenderStyle style;
  SkyKind sky = SkyKind::kNone;
  bool tuned = false;  // ink: bleed_sigma 1.8, so the reach is 4 pixels
};

class PartialRerender : public ::testing::TestWithParam<PartialCase> {};

TEST_P(PartialRerender, TheRegionEqualsAFullFrameAndTheRestIsKept) {
  CB_REQUIRE_GL();
  const Volume volume = makeBundledCumulus(glm::ivec3(32), 1);
  VolumeRenderer renderer;
  std::string err;
  ASSERT_TRUE(renderer.init(&err)) << err;
  renderer.sync(volume, Light{});
  RenderOptions options;
  options.style = GetParam().style;
  options.sky.kind = GetParam().sky;
  if (GetParam().tuned) options.style_params = tunedParams();
  Camera a = Camera::reference();
  a.fov_y_deg = 30.0f;
  const Camera b = a.orbited(40.0f);
  RenderTarget target;
  ASSERT_TRUE(target.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  renderer.render(a, kW, kH, target.fbo(), options);
  const ImageRgba8 full_a = target.readRgba8();
  renderer.render(b, kW, kH, target.fbo(), options);
  const ImageRgba8 full_b = target.readRgba8();
  // R crosses the cloud's outline (x 40..79, y 20..51 from the bottom).
  options.region = glm::ivec4(40, 20, 40, 32);
  renderer.render(a, kW, kH, target.fbo(), options);
  const ImageRgba8 partial = target.readRgba8();

  int worst_inside = 0, worst_outside = 0, differs_a_b = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const int y_up = kH - 1 - y;
      const bool inside = x >= 40 && x < 80 && y_up >= 20 && y_up < 52;
      const ImageRgba8& expected = inside ? full_a : full_b;
      int e = 0;
      for (int c = 0; c < 4; ++c)
        e = std::max(e, std::abs(partial.at(x, y)[c] - expected.at(x, y)[c]));
      (inside ? worst_inside : worst_outside) = std::max(inside ? worst_inside : worst_outside, e);
      if (inside && std::abs(full_a.at(x, y)[0] - full_b.at(x, y)[0]) > 8) ++differs_a_b;
    }
  EXPECT_GT(differs_a_b, 100);  // the two scenes differ inside R, so the test can see stale pixels
  EXPECT_EQ(worst_inside, 0) << renderStyleName(GetParam().style);
  EXPECT_EQ(worst_outside, 0) << renderStyleName(GetParam().style);
}

INSTANTIATE_TEST_SUITE_P(Styles, PartialRerender,
                         ::testing::Values(PartialCase{RenderStyle::kThesis},
                                           PartialCase{RenderStyle::kInk},
                                           PartialCase{RenderStyle::kSketch},
                                           PartialCase{RenderStyle::kThesis, SkyKind::kColour},
                                           PartialCase{RenderStyle::kInk, SkyKind::kNone, true}),
                         [](const ::testing::TestParamInfo<PartialCase>& info) {
                           return std::string(renderStyleName(info.param.style)) +
                                  (info.param.sky != SkyKind::kNone ? "_sky" : "") +
                                  (info.param.tuned ? "_tuned" : "");
                         });

}  // namespace
}  // namespace cb
