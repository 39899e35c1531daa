// The mapping fed by the real brushes (app/brush): a synthetic pen stroke through the stroke
// engine, for each brush, mapped with HMM and seen through the renderer from the paint view.
#include <deque>

#include <gtest/gtest.h>

#include "app/brush/brush_config.h"
#include "app/brush/stroke_engine.h"
#include "app/brush/synthetic_strokes.h"
#include "app/mapping/reference_strokes.h"
#include "app/mapping/stroke_mapper.h"
#include "app/render/volume_renderer.h"
#include "tests/unit/render/gl_test_context.h"

namespace cb {
namespace {

constexpr int kW = 320, kH = 192;

// A steep paint view from above so the whole brush stroke lands on the canvas inside the box.
Camera steepPaintCamera() {
  Camera c;
  c.eye = glm::vec3(0.0f, 2.0f, 1.2f);
  c.target = glm::vec3(0.0f);
  return c;
}

StrokeResult paint(BrushKind kind, uint32_t index) {
  StrokeEngine engine(loadDefaultBrushConfig(), kW, kH);
  engine.selectBrush(kind);
  engine.setPaintView(PaintView{steepPaintCamera()}, Canvas{});
  engine.setNextStrokeIndex(index);
  std::vector<BrushInput> samples = sampleStroke(gentleCurve(kW, kH), 200.0);
  engine.beginStroke(samples.front());
  for (size_t i = 1; i < samples.size(); ++i) engine.addSample(samples[i]);
  return engine.endStroke();
}

TEST(RealBrushMapping, EveryBrushStrokeMapsAndShowsItsFootprint) {
  CB_REQUIRE_GL();
  std::string err;
  VolumeRenderer renderer;
  ASSERT_TRUE(renderer.init(&err)) << err;
  RenderTarget target;
  ASSERT_TRUE(target.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  MappingConfig config;
  config.circles.initial_diameter_px = 128 * kW / 1280;
  StrokeMapper mapper(config);
  mapper.setQuiet(true);
  std::deque<Volume> volumes;  // kept alive: the renderer knows a volume by its address
  for (BrushKind kind : {BrushKind::k2D, BrushKind::k3D, BrushKind::kSkeleton}) {
    StrokeResult stroke = paint(kind, 40 + uint32_t(kind));
    long long painted = 0;
    for (float v : stroke.footprint.values) painted += v > 0.05f;
    ASSERT_GT(painted, 100) << "brush " << int(kind) << " painted almost nothing";
    // A sky box wide enough for the whole stroke, voxels as in the other tests.
    Volume& v = volumes.emplace_back(glm::ivec3(192), glm::vec3(-1.5f), glm::vec3(1.5f));
    MappingReport r = mapper.map(stroke, v);
    ASSERT_FALSE(r.dirty.empty());
    // Every brush's stroke has a body of circles (white at half the peak, mapping_config.h).
    EXPECT_GE(r.circles.size(), 5u) << "brush " << int(kind);
    EXPECT_EQ(r.edges.mapped_pixels, r.edges.leftover_pixels);
    for (const Circle& c : r.circles)
      EXPECT_GE(countCircle(stroke.footprint, nullptr, c.centre, c.radius,
                            effectiveCircleConfig(stroke.footprint, config.circles))
                    .whiteRatio(),
                config.circles.accept_white_ratio);

    renderer.sync(v, Light{});
    RenderOptions opt;
    opt.background = glm::vec4(0.0f);
    renderer.render(stroke.view.camera, kW, kH, target.fbo(), opt);
    ImageRgba8 img = target.readRgba8();
    long long both = 0, either = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        bool p = stroke.footprint.at(x, y) > 0.05f, seen = img.at(x, y)[3] > 127;
        both += p && seen;
        either += p || seen;
      }
    double iou = double(both) / double(either);
    std::printf("brush %d: %lld painted px, %zu circles, covered %.2f, silhouette IoU %.3f\n",
                int(kind), painted, r.circles.size(), r.coveredFraction(), iou);
    EXPECT_GE(iou, 0.85) << "brush " << int(kind);
  }
}

}  // namespace
}  // namespace cb
