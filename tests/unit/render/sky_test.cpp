// The sky behind the clouds: the LIC texture (seed 002) is deterministic and streaky along its
// flow; the GPU sky matches the CPU sky function (sky_function.h) where there is no cloud and is
// hidden behind an opaque cloud; the paper styles keep their paper unless asked.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include <gtest/gtest.h>

#include "app/core/parallel_for.h"
#include "app/render/detail_noise.h"
#include "app/render/render_target.h"
#include "app/render/sky_function.h"
#include "app/render/sky_lic.h"
#include "app/render/volume_renderer.h"
#include "app/volume/scene_generators.h"
#include "tests/unit/render/gl_test_context.h"
#include "tests/unit/render/style_reference.h"

namespace cb {
namespace {

TEST(SkyLic, TheTextureIsTheSameOnEveryRunAndThreadCount) {
  setWorkerThreads(1);
  const std::vector<uint8_t> one = makeLicSkyTexture(128, 12, 0.5f, 7);
  setWorkerThreads(3);
  const std::vector<uint8_t> three = makeLicSkyTexture(128, 12, 0.5f, 7);
  setWorkerThreads(0);
  EXPECT_EQ(one, three);
  EXPECT_EQ(one, makeLicSkyTexture(128, 12, 0.5f, 7));
  EXPECT_NE(one, makeLicSkyTexture(128, 12, 0.5f, 8));  // the seed matters
  // Neither empty nor solid: part of the layer is cloud.
  size_t clear = 0, cloud = 0;
  for (uint8_t v : one) (v < 10 ? clear : v > 60 ? cloud : clear) += v < 10 || v > 60;
  EXPECT_GT(clear, one.size() / 10);
  EXPECT_GT(cloud, one.size() / 20);
  EXPECT_THROW(makeLicSkyTexture(8, 12, 0.5f, 7), std::invalid_argument);
  EXPECT_THROW(makeLicSkyTexture(128, 0, 0.5f, 7), std::invalid_argument);
}

// Mean correlation of the centred image with itself `distance` texels along (or across) the
// flow, over a grid of texels.
double correlation(const ScalarImage& image, uint32_t seed, float distance, bool along) {
  double mean = 0.0;
  for (float v : image.values) mean += v;
  mean /= double(image.values.size());
  double sum = 0.0, norm = 0.0;
  for (int y = 0; y < image.size; y += 3)
    for (int x = 0; x < image.size; x += 3) {
      const glm::vec2 p(float(x) + 0.5f, float(y) + 0.5f);
      glm::vec2 d = licFlow(p, image.size, seed);
      if (!along) d = glm::vec2(-d.y, d.x);
      const double a = image.bilinear(p) - mean, b = image.bilinear(p + distance * d) - mean;
      sum += a * b;
      norm += a * a;
    }
  return sum / norm;
}

TEST(SkyLic, ConvolvedNoiseIsStreakedAlongTheFlow) {
  const uint32_t seed = 11;
  const ScalarImage noise = whiteNoise(128, seed);
  const ScalarImage lic = lineIntegralConvolution(noise, 10, seed);
  const double along = correlation(lic, seed, 4.0f, true);
  const double across = correlation(lic, seed, 4.0f, false);
  const double noise_along = correlation(noise, seed, 4.0f, true);
  const double noise_across = correlation(noise, seed, 4.0f, false);
  std::printf("autocorrelation at 4 texels: LIC along %.3f, across %.3f; noise %.3f, %.3f\n", along,
              across, noise_along, noise_across);
  EXPECT_GT(along, 0.5);    // streaks: what is 4 texels along the flow is alike
  EXPECT_LT(across, 0.15);  // and what is beside them is not
  EXPECT_LT(std::abs(noise_along - noise_across), 0.1);  // the noise itself has no direction
}

// A cumulus seen from below, looking up into the sky, with a sky of `kind`.
struct SkyFrame {
  ImageRgba8 image;
  ReferenceScene scene;
  std::vector<uint8_t> lic;
};

constexpr int kW = 120, kH = 80;

void renderWithSky(SkyKind kind, RenderStyle style, SkyFrame* out,
                   glm::vec4 background = RenderOptions{}.background,
                   bool paper_shows_sky = false) {
  const Volume volume = makeBundledCumulus(glm::ivec3(32), 1);
  Light light;
  light.direction = Light::directionTowards(glm::vec3(-3.0f, 2.0f, 2.0f));
  light.colour = glm::vec3(1.0f, 0.9f, 0.8f);
  VolumeRenderer renderer;
  std::string err;
  ASSERT_TRUE(renderer.init(&err)) << err;
  renderer.sync(volume, light);
  RenderOptions options;
  options.style = style;
  options.background = background;
  options.style_params.ink.sky = paper_shows_sky;
  options.style_params.sketch.sky = paper_shows_sky;
  options.skip_empty_space = true;  // the sky must also show where no ray is cast
  options.sky.kind = kind;
  options.sky.lic_size = 128;
  options.sky.lic_length = 12;
  options.sky.lic_scale = 0.1f;  // texels magnified near the zenith: no mip level in play
  options.sky.lic_coverage = 0.6f;
  if (kind == SkyKind::kImage) {
    // A 40×30 picture with a different colour in every texel (orientation and scaling show).
    auto image = std::make_shared<ImageRgba8>();
    image->width = 40;
    image->height = 30;
    image->pixels.resize(40 * 30 * 4);
    for (int y = 0; y < 30; ++y)
      for (int x = 0; x < 40; ++x) {
        uint8_t* p = image->at(x, y);
        p[0] = uint8_t(x * 6);
        p[1] = uint8_t(y * 8);
        p[2] = uint8_t((x * 37 + y * 91) % 256);
        p[3] = 255;
      }
    options.sky.image = image;
  }
  RenderTarget target;
  ASSERT_TRUE(target.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  Camera camera;
  camera.eye = glm::vec3(0.35f, -2.6f, 0.25f);
  camera.target = glm::vec3(0.0f, 0.2f, 0.0f);
  camera.up = glm::vec3(0.0f, 0.0f, -1.0f);
  camera.fov_y_deg = 40.0f;
  renderer.render(camera, kW, kH, target.fbo(), options);
  out->image = target.readRgba8();
  if (kind == SkyKind::kLic)
    out->lic = makeLicSkyTexture(options.sky.lic_size, options.sky.lic_length,
                                 options.sky.lic_coverage, options.sky.lic_seed);
  ReferenceScene& s = out->scene;
  s.dims = volume.dims();
  s.world_min = volume.worldMin();
  s.world_max = volume.worldMax();
  packDensityAndLight(volume, renderer.lightVolume(), volume.bounds(), &s.voxels);
  s.light = light;
  s.camera = camera;
  s.width = kW;
  s.height = kH;
  s.options = options;
  s.sky_lic = kind == SkyKind::kLic ? &out->lic : nullptr;
  if (style == RenderStyle::kPhysical) s.noise = makeDetailNoise();
}

struct SkyCase {
  SkyKind kind;
  RenderStyle style;
};

class SkyBehindTheCloud : public ::testing::TestWithParam<SkyCase> {};

TEST_P(SkyBehindTheCloud, MatchesTheCpuSkyWhereClearAndIsHiddenWhereOpaque) {
  CB_REQUIRE_GL();
  SkyFrame f;
  renderWithSky(GetParam().kind, GetParam().style, &f);
  // The same frame with no sky on a transparent background: its alpha is the cloud's opacity
  // 1 − T, its colour the cloud's own.
  SkyFrame flat;
  renderWithSky(SkyKind::kNone, GetParam().style, &flat, glm::vec4(0.0f));
  SkyScene sky;
  sky.settings = f.scene.options.sky;
  sky.style = GetParam().style;
  sky.sun_dir = f.scene.light.direction;
  sky.sun_colour = f.scene.light.colour;
  sky.lic = f.scene.sky_lic;
  sky.frame_width = kW;
  sky.frame_height = kH;
  int clear = 0, opaque = 0, worst_clear = 0, worst_opaque = 0, worst_all = 0, compared = 0;
  int sky_differs = 0;
  for (int y = 2; y < kH; y += 4)
    for (int x = 2; x < kW; x += 4) {
      const ReferencePixel ref = referencePixel(f.scene, x, y);
      if (ref.ambiguous) continue;
      glm::vec3 dir, origin;
      f.scene.camera.pixelRay(float(x) + 0.5f, float(y) + 0.5f, kW, kH, &origin, &dir);
      const glm::vec2 pixel = glm::vec2(x, kH - 1 - y) + 0.5f;
      // Posterising is a step: a parameter within 0.01 of a step may round either way.
      if (skyNearPosteriseStep(sky, glm::normalize(dir), 0.01f)) continue;
      const uint8_t* px = f.image.at(x, y);
      int e = 0;
      for (int c = 0; c < 4; ++c)
        e = std::max(e, std::abs(int(px[c]) - int(std::lround(ref.rgba[c] * 255.0f))));
      if (!ref.sensitive) worst_all = std::max(worst_all, e);
      ++compared;
      const glm::vec4 bg = f.scene.options.background;
      const int opacity = flat.image.at(x, y)[3];
      const bool no_cloud = opacity == 0;
      const bool covered = opacity >= 253;
      if (no_cloud) {
        const glm::vec3 expected = skyColour(sky, glm::normalize(dir), pixel);
        int d = 0, differs = 0;
        for (int c = 0; c < 3; ++c) {
          d = std::max(d, std::abs(int(px[c]) - int(std::lround(expected[c] * 255.0f))));
          differs += std::abs(expected[c] - bg[c]) > 0.03f;
        }
        sky_differs += differs > 0;
        worst_clear = std::max(worst_clear, d);
        ++clear;
      }
      // Behind a cloud that is opaque on this ray (T ≈ 0) the sky must not show.
      if (covered && GetParam().style != RenderStyle::kPhysical) {
        int d = 0;
        for (int c = 0; c < 3; ++c)
          d = std::max(d, std::abs(int(px[c]) - int(flat.image.at(x, y)[c])));
        // An opaque ray keeps ≤ 1% transmittance (early termination), so ≤ 1% of the sky.
        worst_opaque = std::max(worst_opaque, d);
        ++opaque;
      }
    }
  std::printf(
      "%s sky, %s: %d rays, %d clear (worst %d/255 vs the CPU sky), %d opaque (worst %d "
      "vs no sky), all rays worst %d vs the CPU reference\n",
      skyKindName(GetParam().kind), renderStyleName(GetParam().style), compared, clear, worst_clear,
      opaque, worst_opaque, worst_all);
  EXPECT_GE(clear, 60);
  EXPECT_GE(sky_differs, clear / 2);  // the sky is not just the old background colour
  EXPECT_LE(worst_clear, 2);
  EXPECT_GE(opaque, GetParam().style == RenderStyle::kPhysical ? 0 : 30);
  EXPECT_LE(worst_opaque, 4);
  EXPECT_LE(worst_all, 4);
}

INSTANTIATE_TEST_SUITE_P(KindsAndStyles, SkyBehindTheCloud,
                         ::testing::Values(SkyCase{SkyKind::kColour, RenderStyle::kThesis},
                                           SkyCase{SkyKind::kLic, RenderStyle::kThesis},
                                           SkyCase{SkyKind::kColour, RenderStyle::kPhysical},
                                           SkyCase{SkyKind::kImage, RenderStyle::kThesis},
                                           SkyCase{SkyKind::kLic, RenderStyle::kCartoon}),
                         [](const ::testing::TestParamInfo<SkyCase>& info) {
                           return std::string(skyKindName(info.param.kind)) + "_" +
                                  renderStyleName(info.param.style);
                         });

TEST(SkyBehindTheCloud, PaperStylesKeepTheirPaperUnlessAsked) {
  CB_REQUIRE_GL();
  for (RenderStyle style : {RenderStyle::kInk, RenderStyle::kSketch}) {
    SkyFrame with, without;
    renderWithSky(SkyKind::kColour, style, &with);
    renderWithSky(SkyKind::kNone, style, &without);
    EXPECT_EQ(with.image.pixels, without.image.pixels) << renderStyleName(style);
  }
}

TEST(SkyBehindTheCloud, PaperStylesShowTheSkyWhenAsked) {
  CB_REQUIRE_GL();
  SkyFrame flat;  // where no ray meets any density (alpha 0 on a transparent background)
  renderWithSky(SkyKind::kNone, RenderStyle::kThesis, &flat, glm::vec4(0.0f));
  for (RenderStyle style : {RenderStyle::kInk, RenderStyle::kSketch}) {
    SkyFrame f, paper;
    renderWithSky(SkyKind::kColour, style, &f, RenderOptions{}.background, true);
    renderWithSky(SkyKind::kNone, style, &paper);
    SkyScene sky;
    sky.settings = f.scene.options.sky;
    sky.style = style;
    sky.sun_dir = f.scene.light.direction;
    sky.sun_colour = f.scene.light.colour;
    int clear = 0, worst = 0, cloud_same = 0, cloud = 0;
    for (int y = 6; y < kH - 6; y += 3)
      for (int x = 6; x < kW - 6; x += 3) {
        bool far_from_cloud = true;  // ink bleeds a few pixels around the outline
        for (int dy = -5; dy <= 5; ++dy)
          for (int dx = -5; dx <= 5; ++dx) far_from_cloud &= flat.image.at(x + dx, y + dy)[3] == 0;
        const uint8_t* px = f.image.at(x, y);
        if (far_from_cloud) {
          glm::vec3 dir, origin;
          f.scene.camera.pixelRay(float(x) + 0.5f, float(y) + 0.5f, kW, kH, &origin, &dir);
          const glm::vec3 e = skyColour(sky, glm::normalize(dir), glm::vec2(x, kH - 1 - y) + 0.5f);
          for (int c = 0; c < 3; ++c)
            worst = std::max(worst, std::abs(int(px[c]) - int(std::lround(e[c] * 255.0f))));
          ++clear;
        } else if (flat.image.at(x, y)[3] >= 240) {
          // Inside the cloud the paper (and ink) is drawn as before.
          ++cloud;
          cloud_same += std::abs(px[0] - paper.image.at(x, y)[0]) <= 1 &&
                        std::abs(px[2] - paper.image.at(x, y)[2]) <= 1;
        }
      }
    EXPECT_GE(clear, 50) << renderStyleName(style);
    EXPECT_LE(worst, 2) << renderStyleName(style);
    EXPECT_GE(cloud, 30) << renderStyleName(style);
    EXPECT_GE(cloud_same, cloud * 9 / 10) << renderStyleName(style);
  }
}

}  // namespace
}  // namespace cb
