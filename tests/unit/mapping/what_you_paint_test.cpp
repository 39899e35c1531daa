// "What you paint is what you get", with nothing but product defaults: the default
// paint camera (app/scene/paint_camera.h) at the painter's default 1280×720 screen, the default
// Canvas, the default sky (1024×256×1024 voxels for the painter's grid 256, its home box the
// thesis's 256³ over [-1,1]³), config/brush.toml and config/mapping.toml as the
// painter loads them, and each real brush through the real StrokeEngine and StrokeMapper. A
// gentle S curve drawn across the drawable region must
//   - land: >= 95 % of its ink pixels show cloud in the paint view (the real renderer),
//   - keep its shape: paint-view silhouette IoU with the ink >= 0.85,
//   - grow a body: circles cover >= 70 % of the footprint (thesis §6.3; edge mapping is for the
//     leftover rim, §6.6),
//   - not be a streak from the side (thesis §6.6.1, Fig. 6.17): anisotropy seen from 90° along
//     the paint view's direction <= 1.3 (the measure of stroke_mapper_render_test.cpp).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>

#include <gtest/gtest.h>

#include "app/brush/brush_config.h"
#include "app/brush/stroke_engine.h"
#include "app/brush/synthetic_strokes.h"
#include "app/core/config_paths.h"
#include "app/mapping/stroke_mapper.h"
#include "app/render/image_io.h"
#include "app/render/volume_renderer.h"
#include "app/scene/drawable_region.h"
#include "app/scene/paint_camera.h"
#include "app/volume/sky_extent.h"
#include "opacity_projection.h"
#include "tests/unit/render/gl_test_context.h"

#include "rendered_opacity.h"

namespace cb {
namespace {

constexpr int kW = 1280, kH = 720;  // PaintSessionSettings' screen; footprint_scale 1

struct Measures {
  long long ink = 0;
  double landed = 0, iou = 0, covered = 0, side_anisotropy = 0;
  size_t circles = 0;
};

// A straight stroke across the drawable region at constant screen height, with the S curve's
// pressure and tilt. On the horizontal canvas it runs across the view, so seen from 90° it is
// seen end-on: its cross-section is what the side-view anisotropy measures. (The S curve's
// swings up and down the screen are swings in depth on the canvas; from the side they read as
// extent along the view however round the cloud's cross-section is.)
SyntheticStroke straightAcross(int w, int h) {
  SyntheticStroke s = gentleCurve(w, h);
  s.name = "straight";
  s.control_points = {{0.15f * w, 0.5f * h}, {0.85f * w, 0.5f * h}};
  return s;
}

class WhatYouPaint : public ::testing::Test {
 protected:
  void SetUp() override {
    CB_REQUIRE_GL();
    std::string err;
    ASSERT_TRUE(renderer.init(&err)) << err;
    ASSERT_TRUE(target.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
    ASSERT_TRUE(std::filesystem::exists(configFile("mapping.toml")));
    mapper = std::make_unique<StrokeMapper>(loadMappingConfig(configFile("mapping.toml")));
    mapper->setQuiet(true);
  }

  std::vector<float> opacity(const Volume& v, const Camera& camera) {
    return test::renderedOpacity(renderer, target, v, camera);
  }

  StrokeResult paint(BrushKind kind, const SyntheticStroke& drawn, const Camera& camera,
                     const Canvas& canvas) {
    StrokeEngine engine(loadDefaultBrushConfig(), kW, kH);
    engine.selectBrush(kind);
    engine.setPaintView(PaintView{camera}, canvas);
    engine.setNextStrokeIndex(90 + uint32_t(kind));
    std::vector<BrushInput> samples = sampleStroke(drawn, 200.0);
    engine.prepareNextStroke();
    engine.beginStroke(samples.front());
    for (size_t i = 1; i < samples.size(); ++i) engine.addSample(samples[i]);
    return engine.endStroke();
  }

  Measures measure(BrushKind kind, const Camera& camera,
                   const SyntheticStroke& drawn = gentleCurve(kW, kH)) {
    const Canvas canvas;
    Measures m;
    StrokeResult stroke = paint(kind, drawn, camera, canvas);
    Volume& v = volumes.emplace_back(makeSkyVolume({256, kDefaultSkySpan}));  // the default sky
    MappingReport report = mapper->map(stroke, v);
    m.circles = report.circles.size();
    m.covered = report.coveredFraction();

    const float empty = mapper->config().circles.empty_threshold;
    std::vector<float> a = opacity(v, camera);
    long long landed = 0, both = 0, either = 0;
    for (size_t i = 0; i < a.size(); ++i) {
      const bool ink = stroke.footprint.values[i] > empty, seen = a[i] > 0.5f;
      m.ink += ink;
      landed += ink && seen;
      both += ink && seen;
      either += ink || seen;
    }
    m.landed = m.ink ? double(landed) / double(m.ink) : 0.0;
    m.iou = either ? double(both) / double(either) : 0.0;

    // Seen end-on along the stroke's screen direction (the paint camera's right axis, level):
    // a distant, narrow camera at the canvas altitude looking along the stroke sees the cloud's
    // cross-section, and a streak along the paint view's rays (thesis Fig. 6.17) is an elongation
    // along the paint direction's image there. For a straight stroke across the screen this is
    // the cross-section of the whole cloud; for a curve, only of its straight parts.
    const glm::vec3 paint_dir = glm::normalize(camera.target - camera.eye);
    const glm::vec3 along = glm::normalize(glm::cross(paint_dir, camera.up));
    glm::vec3 o, d;
    camera.pixelRay(0.5f * kW, 0.5f * kH, kW, kH, &o, &d);
    float t_mid = 0.0f;
    if (!canvas.intersectMidPlane(o, d, &t_mid)) {
      ADD_FAILURE() << "the paint view's centre does not reach the canvas";
      return m;
    }
    Camera side;
    side.target = o + d * t_mid;
    side.eye = side.target - along * 20.0f;
    side.fov_y_deg = 1.2f;
    std::vector<float> s = opacity(v, side);
    const glm::vec3 right = glm::normalize(glm::cross(along, side.up)), up = side.up;
    m.side_anisotropy = test::anisotropyAlong(
        s, kW, kH, glm::vec2(glm::dot(paint_dir, right), -glm::dot(paint_dir, up)));
    keepImages(std::string(brushKindName(kind)) + "_" + drawn.name, stroke.footprint.values, a, s,
               empty);
    std::printf(
        "%-8s %-14s ink %7lld px  landed %.3f  IoU %.3f  circles %3zu covering %.3f  side "
        "anisotropy %.2f\n",
        brushKindName(kind), drawn.name.c_str(), m.ink, m.landed, m.iou, m.circles, m.covered,
        m.side_anisotropy);
    return m;
  }

  // CB_KEEP_FRAMES=DIR writes the ink, the paint-view cloud and the side view as greyscale PNGs,
  // and where they differ: ink that shows cloud white, ink that does not red, cloud without ink
  // blue.
  static void keepImages(const std::string& name, const std::vector<float>& ink,
                         const std::vector<float>& paint_view, const std::vector<float>& side,
                         float empty) {
    const char* keep = std::getenv("CB_KEEP_FRAMES");
    if (!keep) return;
    std::filesystem::create_directories(keep);
    const auto write = [&](const std::string& what, const std::vector<float>& v) {
      ImageRgba8 img;
      img.width = kW;
      img.height = kH;
      img.pixels.resize(size_t(kW) * kH * 4);
      for (size_t i = 0; i < v.size(); ++i) {
        const uint8_t g = uint8_t(std::clamp(v[i], 0.0f, 1.0f) * 255.0f + 0.5f);
        img.pixels[i * 4 + 0] = img.pixels[i * 4 + 1] = img.pixels[i * 4 + 2] = g;
        img.pixels[i * 4 + 3] = 255;
      }
      writePng(std::string(keep) + "/what_you_paint_" + name + "_" + what + ".png", img);
    };
    write("ink", ink);
    write("cloud", paint_view);
    write("side", side);
    ImageRgba8 diff;
    diff.width = kW;
    diff.height = kH;
    diff.pixels.assign(size_t(kW) * kH * 4, 0);
    for (size_t i = 0; i < ink.size(); ++i) {
      const bool inked = ink[i] > empty, seen = paint_view[i] > 0.5f;
      diff.pixels[i * 4 + 0] = inked ? 255 : 0;
      diff.pixels[i * 4 + 1] = inked && seen ? 255 : 0;
      diff.pixels[i * 4 + 2] = seen ? 255 : 0;
      diff.pixels[i * 4 + 3] = 255;
    }
    writePng(std::string(keep) + "/what_you_paint_" + name + "_landed.png", diff);
  }

  std::deque<Volume> volumes;  // kept alive: the renderer knows a volume by its address
  VolumeRenderer renderer;
  RenderTarget target;
  std::unique_ptr<StrokeMapper> mapper;
};

TEST_F(WhatYouPaint, TheStrokeIsDrawnInsideTheDrawableRegion) {
  const Camera camera =
      defaultPaintCamera(Canvas{}, glm::vec3(-1.0f), glm::vec3(1.0f), float(kW) / float(kH));
  const DrawableRegion region(camera, Canvas{}, glm::vec3(-1.0f), glm::vec3(1.0f), kW, kH);
  for (const BrushInput& in : sampleStroke(gentleCurve(kW, kH), 200.0))
    ASSERT_TRUE(region.canLandAt(in.footprint_px)) << in.footprint_px.x << "," << in.footprint_px.y;
}

// What holds today for every brush: the stroke lands (>= 85 % of its ink shows; from
// Camera::reference() 25–41 % did) and most of
// its footprint is grown into circles (thesis §6.3.1 aim 3), not edge-mapped. Before the
// half-maximum whiteness rule the 2D and skeleton brushes grew no circle at all.
TEST_F(WhatYouPaint, EveryBrushsStrokeLandsAndMostOfItIsGrownIntoCircles) {
  const Camera camera =
      defaultPaintCamera(Canvas{}, glm::vec3(-1.0f), glm::vec3(1.0f), float(kW) / float(kH));
  for (BrushKind kind : {BrushKind::k2D, BrushKind::k3D, BrushKind::kSkeleton}) {
    Measures m = measure(kind, camera);
    ASSERT_GT(m.ink, 5000) << brushKindName(kind) << " painted almost nothing";
    EXPECT_GE(m.landed, 0.85) << brushKindName(kind);
    EXPECT_GT(m.covered, 0.5) << brushKindName(kind);
  }
  // The 2D brush's straight stroke is already round in cross-section (the streak measure).
  EXPECT_LE(measure(BrushKind::k2D, camera, straightAcross(kW, kH)).side_anisotropy, 1.3);
}

// the acceptance thresholds, all three brushes at product defaults. What makes them hold
// (app/mapping/README.md): spheres widened so they are opaque out to their circle
// (spheres.outline_chord_voxels), edge pixels placed at their sphere's view depth with a depth
// spread of at most a voxel or R_S/3 (no needles along the rays), the Empty Test on the smallest
// circle (circles follow thin strokes), and a skeleton brush wide enough to be a round cloud at
// 256³.
TEST_F(WhatYouPaint, EveryBrushMeetsTheIssue9Thresholds) {
  const Camera camera =
      defaultPaintCamera(Canvas{}, glm::vec3(-1.0f), glm::vec3(1.0f), float(kW) / float(kH));
  for (BrushKind kind : {BrushKind::k2D, BrushKind::k3D, BrushKind::kSkeleton}) {
    const auto t0 = std::chrono::steady_clock::now();
    Measures m = measure(kind, camera);
    std::printf("%-8s %.1f s\n", brushKindName(kind),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    ASSERT_GT(m.ink, 5000) << brushKindName(kind) << " painted almost nothing";
    EXPECT_GE(m.landed, 0.95) << brushKindName(kind);
    EXPECT_GE(m.iou, 0.85) << brushKindName(kind);
    EXPECT_GE(m.covered, 0.70) << brushKindName(kind);
    const Measures straight = measure(kind, camera, straightAcross(kW, kH));
    EXPECT_LE(straight.side_anisotropy, 1.3) << brushKindName(kind);
  }
}

}  // namespace
}  // namespace cb
