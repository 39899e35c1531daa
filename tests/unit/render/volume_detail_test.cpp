// Still frames cast at the volume's detail (volume_detail.h): the scale rule from the camera
// alone, then the renderer's cast of the bundled cumulus against a ray per pixel.
#include "app/render/volume_detail.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "app/render/image_io.h"
#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"
#include "app/volume/scene_generators.h"
#include "tests/unit/render/gl_test_context.h"

namespace cb {
namespace {

// A camera on the z axis looking down −z, 90° vertical field of view: at view depth z an image
// `h` pixels high spans 2z world units, so a voxel of edge v covers v·h / (2z) pixels.
// The points below are world positions; given in voxels of a 0.04 grid at the origin.
constexpr float kVoxel = 0.04f;
std::vector<glm::vec3> inVoxels(std::vector<glm::vec3> world) {
  for (glm::vec3& p : world) p /= kVoxel;
  return world;
}
float detailOf(const Camera& c, int height, const std::vector<glm::vec3>& world, float floor) {
  return volumeDetailScale(c, height, inVoxels(world), glm::vec3(0.0f), glm::vec3(kVoxel), floor);
}
Camera straightOn() {
  Camera c;
  c.eye = glm::vec3(0.0f, 0.0f, 10.0f);
  c.target = glm::vec3(0.0f);
  c.fov_y_deg = 90.0f;
  return c;
}

TEST(VolumeDetailScale, OneCastPixelPerVoxelAtTheFarthestDepth) {
  const Camera c = straightOn();
  // Points at depths 5 and 8: the farthest decides. v = 0.04, h = 1000: 0.04·1000/16 = 2.5
  // pixels a voxel there → scale 1/2.5 = 0.4.
  const std::vector<glm::vec3> near_and_far = {{0, 0, 5}, {0.5f, 0, 2}};
  EXPECT_NEAR(detailOf(c, 1000, near_and_far, 0.0f), 0.4f, 1e-6f);
  EXPECT_FLOAT_EQ(detailOf(c, 1000, near_and_far, 0.5f), 0.5f);  // the floor
  // 1.6 pixels a voxel (h = 640): 1/1.6 = 0.625 rounded up to the next 1/20: 0.65.
  EXPECT_NEAR(detailOf(c, 640, near_and_far, 0.0f), 0.65f, 1e-6f);
  // Under a pixel a voxel: every pixel cast.
  EXPECT_FLOAT_EQ(detailOf(c, 300, near_and_far, 0.0f), 1.0f);
  // Only the near point: 0.04·1000/10 = 4 pixels a voxel → 0.25.
  EXPECT_NEAR(detailOf(c, 1000, {{0, 0, 5}}, 0.0f), 0.25f, 1e-6f);
}

TEST(VolumeDetailScale, NothingOccupiedOrBehindTheEyeCastsEveryPixel) {
  const Camera c = straightOn();
  EXPECT_FLOAT_EQ(detailOf(c, 1000, {}, 0.0f), 1.0f);
  EXPECT_FLOAT_EQ(detailOf(c, 1000, {{0, 0, 12}}, 0.0f), 1.0f);  // behind
  EXPECT_FLOAT_EQ(detailOf(c, 0, {{0, 0, 5}}, 0.0f), 1.0f);
}

// At rest no coarser than half per axis; moving no finer than the volume needs, down to 3/20, and
// never finer than the moving scale asked.
TEST(VolumeDetailScale, StillAndMovingFramesKeepTheirFloors) {
  EXPECT_FLOAT_EQ(detailCastScale(1.0f, false, 0.25f), kMinStillDetailScale);
  EXPECT_FLOAT_EQ(detailCastScale(1.0f, false, 0.7f), 0.7f);
  EXPECT_FLOAT_EQ(detailCastScale(1.0f, false, 1.0f), 1.0f);
  EXPECT_FLOAT_EQ(detailCastScale(0.5f, true, 0.1f), kMinMovingDetailScale);
  EXPECT_FLOAT_EQ(detailCastScale(0.5f, true, 0.35f), 0.35f);
  EXPECT_FLOAT_EQ(detailCastScale(0.5f, true, 0.8f), 0.5f);
}

constexpr int kW = 640, kH = 360;

struct Frame {
  ImageRgba8 image;
  int cast_width = 0;
};

Frame renderFrame(VolumeRenderer& r, const RenderOptions& options) {
  RenderTarget target;
  std::string err;
  EXPECT_TRUE(target.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  r.render(Camera::reference(), kW, kH, target.fbo(), options);
  return {readFramebufferRgba8(target.fbo(), kW, kH), r.lastStats().width};
}

// The bundled cumulus at 64³ on 640×360 from the reference camera: ~3 pixels a voxel, so the
// painter's still frame is cast at half the pixels per axis.
class VolumeDetailRender : public ::testing::Test {
 protected:
  void SetUp() override {
    CB_REQUIRE_GL();
    std::string err;
    ASSERT_TRUE(renderer.init(&err)) << err;
    renderer.sync(cumulus, Light{});
  }
  const Volume cumulus = makeBundledCumulus(glm::ivec3(64));  // the renderer reads it later
  VolumeRenderer renderer;
};

// `image` against `reference`: mean under 0.5/255 and 99 % of channels within 2/255, the bilinear
// upscale of a field that is trilinear between voxels sampled at ≥ 1 ray a voxel (the product's
// views measured 0.03–0.13 mean, p99 1; these small clouds have relatively more edge).
void expectLooksTheSame(const ImageRgba8& reference, const ImageRgba8& image,
                        const std::string& what) {
  std::vector<int> diff(reference.pixels.size());
  double sum = 0.0;
  for (size_t i = 0; i < diff.size(); ++i) {
    diff[i] = std::abs(int(reference.pixels[i]) - int(image.pixels[i]));
    sum += diff[i];
  }
  std::sort(diff.begin(), diff.end());
  const double mean = sum / double(diff.size());
  const int p99 = diff[diff.size() * 99 / 100];
  std::printf("%s: mean %.3f/255, p99 %d/255, max %d/255\n", what.c_str(), mean, p99, diff.back());
  EXPECT_LT(mean, 0.5) << what;
  EXPECT_LE(p99, 2) << what;
}

// A moving frame at the moving scale ½ cast at the volume's detail, against the moving frame at ½
// (expectLooksTheSame); returns the scale it was cast at (never below the moving floor).
float expectMovingFrameAtDetail(VolumeRenderer& renderer, const std::string& what) {
  RenderOptions moving;
  moving.scale = 0.5f;
  moving.moving = true;
  RenderOptions at_detail = moving;
  at_detail.cast_at_volume_detail = true;
  const float scale = renderer.castScale(Camera::reference(), kH, at_detail);
  EXPECT_GE(scale, kMinMovingDetailScale);
  const Frame half = renderFrame(renderer, moving);
  const Frame detail = renderFrame(renderer, at_detail);
  EXPECT_EQ(half.cast_width, kW / 2);
  EXPECT_EQ(detail.cast_width, int(std::lround(kW * scale)));
  expectLooksTheSame(half.image, detail.image,
                     what + " moving at " + std::to_string(scale) + " against 0.5");
  return scale;
}

// Against a ray per pixel, at half the rays per axis.
TEST_F(VolumeDetailRender, TheStillFrameIsCastAtHalfTheRaysAndLooksTheSame) {
  for (RenderStyle style : {RenderStyle::kThesis, RenderStyle::kPhysical}) {
    RenderOptions every_pixel;
    every_pixel.style = style;
    RenderOptions at_detail = every_pixel;
    at_detail.cast_at_volume_detail = true;
    EXPECT_FLOAT_EQ(renderer.castScale(Camera::reference(), kH, at_detail), 0.5f);
    const Frame full = renderFrame(renderer, every_pixel);
    const Frame detail = renderFrame(renderer, at_detail);
    EXPECT_EQ(full.cast_width, kW);
    EXPECT_EQ(detail.cast_width, kW / 2);
    expectLooksTheSame(full.image, detail.image, renderStyleName(style));
  }
}

// A moving frame of that cloud: no finer than the voxels need (~3 pixels a voxel at its far
// side: a third).
TEST_F(VolumeDetailRender, AMovingFrameIsCastNoFinerThanTheVolumeNeeds) {
  EXPECT_LT(expectMovingFrameAtDetail(renderer, "64^3"), 0.5f);
}

// A coarse volume (the painter's morph and wind play on a half-resolution copy): the cumulus at
// 32³, ~6 pixels a voxel at its far side, moving, is cast coarser than a quarter, as far as its
// voxels allow.
TEST(VolumeDetailCoarse, AMovingFrameOfACoarseVolumeIsCastAtItsVoxels) {
  CB_REQUIRE_GL();
  VolumeRenderer renderer;
  std::string err;
  ASSERT_TRUE(renderer.init(&err)) << err;
  const Volume coarse = makeBundledCumulus(glm::ivec3(32));
  renderer.sync(coarse, Light{});
  EXPECT_LT(expectMovingFrameAtDetail(renderer, "32^3"), 0.25f);
}

// Styles with a screen pass or screen derivatives, jittered frames, a textured sky and the option
// off are cast as asked.
TEST_F(VolumeDetailRender, OtherFramesAreCastAsAsked) {
  RenderOptions o;
  o.cast_at_volume_detail = true;
  for (RenderStyle style : {RenderStyle::kInk, RenderStyle::kCartoon, RenderStyle::kSketch}) {
    o.style = style;
    EXPECT_FLOAT_EQ(renderer.castScale(Camera::reference(), kH, o), 1.0f) << renderStyleName(style);
  }
  o.style = RenderStyle::kThesis;
  RenderOptions jittered = o;
  jittered.jitter = glm::vec2(0.25f, 0.0f);
  EXPECT_FLOAT_EQ(renderer.castScale(Camera::reference(), kH, jittered), 1.0f);
  RenderOptions lic = o;
  lic.sky.kind = SkyKind::kLic;
  EXPECT_FLOAT_EQ(renderer.castScale(Camera::reference(), kH, lic), 1.0f);
  RenderOptions off = o;
  off.cast_at_volume_detail = false;
  EXPECT_FLOAT_EQ(renderer.castScale(Camera::reference(), kH, off), 1.0f);
  // And the ink frame asked at detail is the ray-per-pixel frame, bit for bit.
  RenderOptions ink = o, ink_every = o;
  ink.style = ink_every.style = RenderStyle::kInk;
  ink_every.cast_at_volume_detail = false;
  const Frame a = renderFrame(renderer, ink), b = renderFrame(renderer, ink_every);
  EXPECT_EQ(a.cast_width, kW);
  EXPECT_TRUE(a.image.pixels == b.image.pixels);
}

}  // namespace
}  // namespace cb
