// The skeleton brush's spine (thesis §5.2.1): Verlet + 10 constraint iterations keep the three
// segments at their length and the joints on or above the soft paper, whatever the pen does.
#include <gtest/gtest.h>

#include "app/brush/skeleton_brush.h"
#include "brush_test_support.h"

namespace cb::test {
namespace {

TEST(SkeletonBrush, SpineKeepsItsSegmentLengthsAndStaysOnThePaper) {
  BrushConfig config;
  SkeletonBrush brush(config);
  Footprint fp(256, 160);
  std::vector<BrushInput> samples = sampleStroke(gentleCurve(256, 160), 200.0);
  auto point = [](const BrushInput& in) {
    return StrokePoint{in.footprint_px, in.pressure, in.tilt_x_deg, in.tilt_y_deg, in.t_ns};
  };
  brush.beginStroke(0, point(samples[0]), &fp);
  const float L = config.skeleton.segment_length_px;
  for (size_t i = 1; i < samples.size(); ++i) {
    brush.continueStroke(point(samples[i]), &fp);
    const auto& j = brush.joints();
    for (int k = 0; k < 3; ++k)
      ASSERT_NEAR(glm::length(j[k + 1] - j[k]), L, 0.05f * L) << "sample " << i << " segment " << k;
    for (int k = 1; k < 4; ++k) ASSERT_GE(j[k].y, -config.skeleton.paper_softness_px - 1e-3f);
    // Joint 0 is the rod: it follows the pen, at most one internal step (1 ms) behind.
    ASSERT_NEAR(j[0].x, samples[i].footprint_px.x, 0.5f);
    ASSERT_NEAR(j[0].z, samples[i].footprint_px.y, 0.5f);
  }
  // Fixed internal time step: one step per millisecond of pen time (plus the settling steps).
  int64_t duration_ms = (samples.back().t_ns - samples.front().t_ns) / 1000000;
  EXPECT_NEAR(double(brush.stepCount()), double(duration_ms + 40), 2.0);
  EXPECT_GT(inkedPixels(fp), 300);
}

TEST(SkeletonBrush, HarderPressureSplaysMoreBristlesOntoThePaper) {
  BrushConfig config;
  auto dotArea = [&](float pressure) {
    SkeletonBrush brush(config);
    Footprint fp(128, 128);
    brush.beginStroke(0, StrokePoint{{64.0f, 64.0f}, pressure, 0.0f, 0.0f, 0}, &fp);
    return inkedPixels(fp);
  };
  EXPECT_GT(dotArea(0.9f), dotArea(0.5f));
  EXPECT_GT(dotArea(0.5f), dotArea(0.2f));
}

}  // namespace
}  // namespace cb::test
