// Properties every brush must keep: area grows with pressure, the 3D brush's tilt makes
// an asymmetric split tip, the footprint does not depend on the report rate, a one-sample stroke
// leaves a mark, fast strokes disperse ink, every change is inside the returned rectangle, and the
// footprint is deterministic.
#include <cmath>

#include <gtest/gtest.h>

#include "app/brush/brush_3d.h"
#include "app/brush/ink_volume.h"
#include "app/core/parallel_for.h"
#include "brush_test_support.h"

namespace cb::test {
namespace {

const BrushKind kAllBrushes[] = {BrushKind::k2D, BrushKind::k3D, BrushKind::kSkeleton};

std::string nameOf(BrushKind k) {
  return brushKindName(k);
}

StrokeResult paintWith(BrushKind kind, const SyntheticStroke& stroke, double rate_hz, int w, int h,
                       const BrushConfig& base = BrushConfig{}) {
  BrushConfig config = base;
  config.default_brush = kind;
  StrokeEngine engine(config, w, h);
  return paintStroke(&engine, sampleStroke(stroke, rate_hz));
}

SyntheticStroke straightLine(int w, int h, float pressure, float speed = 300.0f) {
  SyntheticStroke s;
  s.control_points = {{0.2f * w, 0.5f * h}, {0.8f * w, 0.5f * h}};
  s.pressure = [pressure](float) { return pressure; };
  s.speed_px_s = speed;
  return s;
}

TEST(BrushProperties, AreaGrowsMonotonicallyWithPressure) {
  for (BrushKind kind : kAllBrushes) {
    int previous = 0;
    for (float p : {0.15f, 0.3f, 0.45f, 0.6f, 0.75f, 0.9f, 1.0f}) {
      int area = inkedPixels(paintWith(kind, straightLine(256, 128, p), 200.0, 256, 128).footprint);
      EXPECT_GT(area, previous) << nameOf(kind) << " at pressure " << p;
      previous = area;
    }
  }
}

// Ink in the left and right halves of a single 3D-brush sample and of a painted dot.
struct Halves {
  double left = 0, right = 0, top = 0, bottom = 0;
};
Halves solidHalves(const Footprint& fp, glm::vec2 centre) {
  Halves h;
  for (int y = 0; y < fp.height; ++y)
    for (int x = 0; x < fp.width; ++x) {
      float v = fp.at(x, y) > 0.8f ? 1.0f : 0.0f;  // the rounded, solid body
      (x + 0.5f < centre.x ? h.left : h.right) += v;
      (y + 0.5f < centre.y ? h.top : h.bottom) += v;
    }
  return h;
}

Footprint paintDot(BrushKind kind, float pressure, float tilt_x, float tilt_y) {
  BrushConfig config;
  config.default_brush = kind;
  StrokeEngine engine(config, 128, 128);
  BrushInput in;
  in.footprint_px = {64.0f, 64.0f};
  in.pressure = pressure;
  in.tilt_x_deg = tilt_x;
  in.tilt_y_deg = tilt_y;
  return paintStroke(&engine, {in}).footprint;
}

TEST(BrushProperties, TiltMakesThe3DBrushAsymmetricInTheTiltDirection) {
  const glm::vec2 c(64.0f, 64.0f);
  Halves upright = solidHalves(paintDot(BrushKind::k3D, 0.8f, 0, 0), c);
  ASSERT_GT(upright.left, 50);
  EXPECT_NEAR(upright.left / upright.right, 1.0, 0.25);
  // Leaning towards +x: the rounded body lies under the lean (+x), the split tip opposite.
  Halves right = solidHalves(paintDot(BrushKind::k3D, 0.8f, 40, 0), c);
  EXPECT_GT(right.right, 1.5 * right.left);
  Halves left = solidHalves(paintDot(BrushKind::k3D, 0.8f, -40, 0), c);
  EXPECT_GT(left.left, 1.5 * left.right);
  Halves towards_user = solidHalves(paintDot(BrushKind::k3D, 0.8f, 0, 40), c);
  EXPECT_GT(towards_user.bottom, 1.5 * towards_user.top);
  EXPECT_NEAR(towards_user.left / towards_user.right, 1.0, 0.3);
}

TEST(BrushProperties, TheTwoDBrushIgnoresTilt) {
  Footprint upright = paintDot(BrushKind::k2D, 0.6f, 0, 0);
  Footprint tilted = paintDot(BrushKind::k2D, 0.6f, 45, -30);
  EXPECT_EQ(upright.values, tilted.values);
}

TEST(BrushProperties, LightPressureIsSparseAndHardPressureSolid) {
  // Solid fraction of the inked area of a single 3D sample (Fig. 5.7).
  auto solidity = [](const Footprint& fp) {
    return double(inkedPixels(fp, 0.8f)) / std::max(1, inkedPixels(fp, 0.05f));
  };
  double light = solidity(paintDot(BrushKind::k3D, 0.1f, 0, 0));
  double hard = solidity(paintDot(BrushKind::k3D, 1.0f, 0, 0));
  EXPECT_LT(light, 0.5);
  EXPECT_GT(hard, 0.6);
  EXPECT_GT(hard, light + 0.2);
}

TEST(BrushProperties, FootprintIsIndependentOfTheReportRate) {
  for (BrushKind kind : kAllBrushes) {
    SyntheticStroke s = gentleCurve(256, 160);
    Footprint slow = paintWith(kind, s, 100.0, 256, 160).footprint;
    Footprint fast = paintWith(kind, s, 400.0, 256, 160).footprint;
    ASSERT_GT(inkedPixels(slow), 500) << nameOf(kind);
    EXPECT_GT(inkIoU(slow, fast), 0.93) << nameOf(kind);
    EXPECT_LT(meanAbsDifference(slow, fast), 0.01) << nameOf(kind);
    EXPECT_NEAR(inkSum(slow) / inkSum(fast), 1.0, 0.03) << nameOf(kind);
  }
}

TEST(BrushProperties, OneSampleStrokeLeavesADot) {
  for (BrushKind kind : kAllBrushes) {
    Footprint dot = paintDot(kind, 0.5f, 10, 0);
    EXPECT_GT(inkedPixels(dot), 10) << nameOf(kind);
  }
}

TEST(BrushProperties, FastStrokesDisperseInk) {
  for (BrushKind kind : kAllBrushes) {
    Footprint slow =
        paintWith(kind, straightLine(384, 128, 0.8f, 200.0f), 200.0, 384, 128).footprint;
    Footprint fast =
        paintWith(kind, straightLine(384, 128, 0.8f, 6000.0f), 200.0, 384, 128).footprint;
    // Within the slow stroke's area, how much of the fast stroke is laid solid.
    auto solid_within = [&slow](const Footprint& fp) {
      int area = 0, solid = 0;
      for (size_t i = 0; i < fp.values.size(); ++i)
        if (slow.values[i] > 0.05f) {
          ++area;
          solid += fp.values[i] > 0.5f;
        }
      return double(solid) / std::max(area, 1);
    };
    double slow_solid = solid_within(slow), fast_solid = solid_within(fast);
    EXPECT_LT(fast_solid, 0.8 * slow_solid) << nameOf(kind);
  }
}

TEST(BrushProperties, ChangesStayInsideTheReturnedRectangle) {
  for (BrushKind kind : kAllBrushes) {
    BrushConfig config;
    config.default_brush = kind;
    StrokeEngine engine(config, 256, 160);
    std::vector<BrushInput> samples = sampleStroke(gentleCurve(256, 160), 200.0);
    Footprint before(256, 160);
    size_t changed_outside = 0, changed_total = 0;
    for (size_t i = 0; i < samples.size(); ++i) {
      const FootprintRect r =
          i == 0 ? engine.beginStroke(samples[i]) : engine.addSample(samples[i]);
      const Footprint& now = engine.footprint();
      for (int y = 0; y < now.height; ++y)
        for (int x = 0; x < now.width; ++x)
          if (now.at(x, y) != before.at(x, y)) {
            ++changed_total;
            changed_outside += !(x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1);
          }
      before = now;
    }
    EXPECT_GT(changed_total, 100u) << nameOf(kind);
    EXPECT_EQ(changed_outside, 0u) << nameOf(kind);
  }
}

TEST(BrushProperties, SameStrokeGivesIdenticalBytesOnAnyThreadCount) {
  for (BrushKind kind : kAllBrushes) {
    SyntheticStroke s = gentleCurve(256, 160);
    s.speed_px_s = 2500.0f;  // dispersion on: the per-stroke noise is exercised too
    setWorkerThreads(1);
    Footprint one = paintWith(kind, s, 200.0, 256, 160).footprint;
    setWorkerThreads(8);
    Footprint eight = paintWith(kind, s, 200.0, 256, 160).footprint;
    setWorkerThreads(0);
    EXPECT_EQ(one.values, eight.values) << nameOf(kind);
  }
}

TEST(BrushProperties, StrokeIndexSeedsTheDispersionPattern) {
  BrushConfig config;
  config.default_brush = BrushKind::k3D;
  SyntheticStroke s = straightLine(256, 128, 0.8f, 3000.0f);
  StrokeEngine engine(config, 256, 128);
  Footprint first = paintStroke(&engine, sampleStroke(s, 200.0)).footprint;
  Footprint second = paintStroke(&engine, sampleStroke(s, 200.0)).footprint;
  engine.setNextStrokeIndex(0);
  Footprint again = paintStroke(&engine, sampleStroke(s, 200.0)).footprint;
  EXPECT_NE(first.values, second.values);
  EXPECT_EQ(first.values, again.values);
}

TEST(BrushProperties, CachedSamplesEqualFreshOnes) {
  BrushConfig config;
  auto ink = std::make_shared<InkVolume>(config.brush3d.ink_volume_size, config.brush3d.ink_seed);
  Brush3D cached(config, ink), fresh(config, ink);
  fresh.setCaching(false);
  std::vector<BrushInput> samples = sampleStroke(tiltSweep(256, 128), 200.0);
  Footprint a(256, 128), b(256, 128);
  auto point = [](const BrushInput& in) {
    return StrokePoint{in.footprint_px, in.pressure, in.tilt_x_deg, in.tilt_y_deg, in.t_ns};
  };
  cached.beginStroke(3, point(samples[0]), &a);
  fresh.beginStroke(3, point(samples[0]), &b);
  for (size_t i = 1; i < samples.size(); ++i) {
    cached.continueStroke(point(samples[i]), &a);
    fresh.continueStroke(point(samples[i]), &b);
  }
  EXPECT_EQ(a.values, b.values);
  EXPECT_GT(cached.cacheHits(), 0u);  // a sweep of tilt still reuses some slices
  EXPECT_EQ(fresh.cacheHits() + fresh.cacheMisses(), cached.cacheHits() + cached.cacheMisses());
  EXPECT_EQ(fresh.cacheHits(), 0u);
}

}  // namespace
}  // namespace cb::test
