// Golden images of the volume renderer (EGL surfaceless, llvmpipe), 320×200, 64³ volumes.
// Each case renders a scene and compares it with tests/golden/render/<name>.png: every channel
// of every pixel within kMaxPixelError and the mean absolute error within kMaxMeanError.
//
// Regenerate on purpose (after a deliberate change to the image), then review and commit them:
//   CB_UPDATE_GOLDENS=1 ./build/tests/golden/render/render_golden_test
// On a mismatch the rendered image is written next to the test binary as <name>.actual.png.
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <gtest/gtest.h>

#include "app/render/image_io.h"
#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"
#include "app/volume/scene_generators.h"
#include "tests/support/golden_image.h"
#include "tests/unit/render/gl_test_context.h"

namespace cb {
namespace {

constexpr int kW = 320, kH = 200;
constexpr int kMaxPixelError = 6;       // of 255, any channel of any pixel
constexpr double kMaxMeanError = 0.25;  // of 255, mean over all channels

std::string goldenPath(const std::string& name) {
  return std::string(CB_SOURCE_DIR) + "/tests/golden/render/" + name + ".png";
}

void expectMatchesGolden(const std::string& name, const Volume& volume, const Light& light,
                         const Camera& camera, RenderOptions options = {}) {
  CB_REQUIRE_GL();
  VolumeRenderer renderer;
  std::string err;
  ASSERT_TRUE(renderer.init(&err)) << err;
  renderer.sync(volume, light);
  RenderTarget target;
  ASSERT_TRUE(target.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  renderer.render(camera, kW, kH, target.fbo(), options);
  test::expectImageMatchesGolden(goldenPath(name), name, target.readRgba8(), kMaxPixelError,
                                 kMaxMeanError);
}

TEST(RenderGolden, EmptyVolume) {
  expectMatchesGolden("empty", Volume(glm::ivec3(64)), Light{}, Camera::reference());
}

TEST(RenderGolden, SingleVoxel) {
  expectMatchesGolden("single_voxel", makeSingleVoxel(glm::ivec3(64), {30, 34, 31}), Light{},
                      Camera::reference());
}

TEST(RenderGolden, Sphere) {
  expectMatchesGolden("sphere", makeSphere(glm::ivec3(64), glm::vec3(0.1f, 0.0f, -0.1f), 0.6f),
                      Light{}, Camera::reference());
}

TEST(RenderGolden, BundledCloudLitFromTheLeft) {
  Light light;
  light.direction = Light::directionTowards(glm::vec3(-4.0f, 2.0f, 2.5f));
  expectMatchesGolden("cumulus_lit_left", makeBundledCumulus(glm::ivec3(64), 1), light,
                      Camera::reference());
}

TEST(RenderGolden, BundledCloudLitFromTheRight) {
  Light light;
  light.direction = Light::directionTowards(glm::vec3(3.0f, 1.0f, -4.0f));
  light.colour = glm::vec3(1.0f, 0.85f, 0.7f);  // a low, warm sun
  expectMatchesGolden("cumulus_lit_right", makeBundledCumulus(glm::ivec3(64), 1), light,
                      Camera::reference());
}

TEST(RenderGolden, CameraInsideTheCloud) {
  Camera camera;
  camera.eye = glm::vec3(0.05f, -0.1f, 0.1f);  // inside the cumulus's core
  camera.target = glm::vec3(1.0f, 0.2f, 0.6f);
  camera.fov_y_deg = 60.0f;
  RenderOptions options;
  options.extinction_per_voxel = 0.05f;  // thin enough to see through the fog around the eye
  expectMatchesGolden("camera_inside", makeBundledCumulus(glm::ivec3(64), 1), Light{}, camera,
                      options);
}

// Every render style (render_style.h) on the bundled cumulus at 64³: two views (the reference
// 3/4 view and a low view from the other side) × two suns (high from the left; low, warm, from
// the right). The thesis style's reference-view images are cumulus_lit_{left,right} above.
struct StyleCase {
  RenderStyle style;
  const char* view;
  const char* light;
};

Camera styleView(const std::string& view) {
  if (view == "reference") return Camera::reference();
  Camera camera = Camera::reference();
  camera.eye = glm::vec3(-2.4f, 0.4f, 1.9f);
  camera.target = glm::vec3(0.0f, 0.05f, 0.0f);
  return camera;
}

Light styleLight(const std::string& light) {
  Light l;
  if (light == "left") {
    l.direction = Light::directionTowards(glm::vec3(-4.0f, 2.0f, 2.5f));
  } else {
    l.direction = Light::directionTowards(glm::vec3(3.0f, 1.0f, -4.0f));
    l.colour = glm::vec3(1.0f, 0.85f, 0.7f);
  }
  return l;
}

class RenderStyleGolden : public ::testing::TestWithParam<StyleCase> {};

TEST_P(RenderStyleGolden, BundledCloud) {
  const StyleCase& c = GetParam();
  RenderOptions options;
  options.style = c.style;
  static const Volume cloud = makeBundledCumulus(glm::ivec3(64), 1);
  expectMatchesGolden(
      std::string("style_") + renderStyleName(c.style) + "_" + c.view + "_" + c.light, cloud,
      styleLight(c.light), styleView(c.view), options);
}

std::vector<StyleCase> allStyleCases() {
  std::vector<StyleCase> cases;
  for (RenderStyle style : kAllRenderStyles)
    for (const char* view : {"reference", "side"})
      for (const char* light : {"left", "right"})
        if (style != RenderStyle::kThesis || std::string(view) != "reference")
          cases.push_back({style, view, light});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(AllStyles, RenderStyleGolden, ::testing::ValuesIn(allStyleCases()),
                         [](const ::testing::TestParamInfo<StyleCase>& info) {
                           return std::string(renderStyleName(info.param.style)) + "_" +
                                  info.param.view + "_" + info.param.light;
                         });

}  // namespace
}  // namespace cb
