// The mapping seen through the real renderer (VolumeRenderer on EGL surfaceless, llvmpipe):
// accumulated opacity is the alpha of a render over a transparent background.
#include <deque>

#include <gtest/gtest.h>

#include "app/mapping/reference_strokes.h"
#include "app/mapping/stroke_mapper.h"
#include "app/render/volume_renderer.h"
#include "opacity_projection.h"
#include "tests/unit/render/gl_test_context.h"

#include "rendered_opacity.h"

namespace cb {
namespace {

constexpr int kW = 320, kH = 192;

class MappedCloudRender : public ::testing::Test {
 protected:
  void SetUp() override {
    CB_REQUIRE_GL();
    std::string err;
    ASSERT_TRUE(renderer.init(&err)) << err;
    ASSERT_TRUE(target.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
    MappingConfig c;
    c.circles.initial_diameter_px = 128 * kW / 1280;
    mapper = std::make_unique<StrokeMapper>(c);
    mapper->setQuiet(true);
  }

  std::vector<float> opacity(const Volume& v, const Camera& camera) {
    return test::renderedOpacity(renderer, target, v, camera);
  }

  double silhouetteIoU(const Volume& v, const StrokeResult& s) {
    std::vector<float> a = opacity(v, s.view.camera);
    long long both = 0, either = 0;
    for (size_t i = 0; i < a.size(); ++i) {
      bool painted = s.footprint.values[i] > 0.05f, seen = a[i] > 0.5f;
      both += painted && seen;
      either += painted || seen;
    }
    return either ? double(both) / double(either) : 0.0;
  }

  double anisotropyFromSide(const Volume& v, const StrokeResult& s) {
    const Camera side = s.view.camera.orbited(90.0f);
    std::vector<float> a = opacity(v, side);
    glm::vec3 paint_dir = glm::normalize(s.view.camera.target - s.view.camera.eye);
    glm::vec3 f = glm::normalize(side.target - side.eye);
    glm::vec3 right = glm::normalize(glm::cross(f, side.up)), up = glm::cross(right, f);
    return test::anisotropyAlong(a, kW, kH,
                                 glm::vec2(glm::dot(paint_dir, right), -glm::dot(paint_dir, up)));
  }

  // The renderer recognises a volume by its address and generation, so every volume a test
  // renders stays alive (a new Volume at a freed one's address would look unchanged).
  Volume& newVolume() { return volumes.emplace_back(glm::ivec3(128)); }

  std::deque<Volume> volumes;
  VolumeRenderer renderer;
  RenderTarget target;
  std::unique_ptr<StrokeMapper> mapper;
};

TEST_F(MappedCloudRender, PaintViewSilhouetteMatchesTheFootprint) {
  for (auto make : {makeThickStroke, makeHeart}) {
    StrokeResult s = make(kW, kH, 31);
    for (MappingMethod method : {MappingMethod::kHybrid, MappingMethod::kRayMarching}) {
      Volume& v = newVolume();
      mapper->map(s, v, method);
      double iou = silhouetteIoU(v, s);
      std::printf("%s silhouette IoU (renderer) %.3f\n", toString(method), iou);
      EXPECT_GE(iou, 0.85) << toString(method);
    }
  }
}

TEST_F(MappedCloudRender, SeenFromTheSideRayMarchingStreaksAndHybridDoesNot) {
  StrokeResult s = makeThickStroke(kW, kH, 32);
  Volume& rmm = newVolume();
  Volume& hmm = newVolume();
  mapper->map(s, rmm, MappingMethod::kRayMarching);
  mapper->map(s, hmm, MappingMethod::kHybrid);
  double a_rmm = anisotropyFromSide(rmm, s);
  double a_hmm = anisotropyFromSide(hmm, s);
  std::printf("anisotropy from 90 deg (renderer): RMM %.2f HMM %.2f\n", a_rmm, a_hmm);
  EXPECT_GE(a_rmm, 2.0);
  EXPECT_LE(a_hmm, 1.3);
}

}  // namespace
}  // namespace cb
