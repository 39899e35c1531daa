// Bad input: NaN or out-of-range pressure, tilt and position are clamped or dropped
// and counted, never propagated into the footprint.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "brush_test_support.h"

namespace cb::test {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(BrushInputSanitizer, DropsNonFiniteAndRepairsOutOfRange) {
  InputHistory history;
  InputStats stats;
  BrushInput ok{{10.0f, 10.0f}, 0.5f, 5.0f, -5.0f, 100};
  EXPECT_TRUE(sanitizeBrushInput(&ok, 64, 64, 8.0f, &history, &stats));

  BrushInput nan_pressure = ok;
  nan_pressure.pressure = kNaN;
  EXPECT_FALSE(sanitizeBrushInput(&nan_pressure, 64, 64, 8.0f, &history, &stats));
  BrushInput inf_position = ok;
  inf_position.footprint_px.y = kInf;
  EXPECT_FALSE(sanitizeBrushInput(&inf_position, 64, 64, 8.0f, &history, &stats));
  EXPECT_EQ(stats.dropped_non_finite, 2u);

  BrushInput loud{{10.0f, 10.0f}, 7.0f, kNaN, 400.0f, 200};
  EXPECT_TRUE(sanitizeBrushInput(&loud, 64, 64, 8.0f, &history, &stats));
  EXPECT_EQ(loud.pressure, 1.0f);
  EXPECT_EQ(loud.tilt_x_deg, 5.0f);   // the previous valid tilt
  EXPECT_EQ(loud.tilt_y_deg, 90.0f);  // clamped
  EXPECT_EQ(stats.clamped_pressure, 1u);
  EXPECT_EQ(stats.repaired_tilt, 1u);

  BrushInput far{{-1e9f, 30.0f}, -0.5f, 0.0f, 0.0f, 150};  // also earlier than the last one
  EXPECT_TRUE(sanitizeBrushInput(&far, 64, 64, 8.0f, &history, &stats));
  EXPECT_EQ(far.footprint_px.x, -8.0f);
  EXPECT_EQ(far.pressure, 0.0f);
  EXPECT_EQ(far.t_ns, 200);
  EXPECT_EQ(stats.clamped_position, 1u);
  EXPECT_EQ(stats.repaired_timestamp, 1u);
  EXPECT_EQ(stats.accepted, 3u);
}

TEST(BrushInputSanitizer, BadSamplesNeverReachTheFootprint) {
  for (BrushKind kind : {BrushKind::k2D, BrushKind::k3D, BrushKind::kSkeleton}) {
    BrushConfig config;
    config.default_brush = kind;
    std::vector<BrushInput> clean = sampleStroke(gentleCurve(192, 128), 200.0);
    std::vector<BrushInput> dirty;
    for (size_t i = 0; i < clean.size(); ++i) {
      dirty.push_back(clean[i]);
      if (i % 7 == 3) {  // interleave garbage that must be dropped
        BrushInput bad = clean[i];
        bad.pressure = kNaN;
        dirty.push_back(bad);
        bad = clean[i];
        bad.footprint_px.x = kNaN;
        dirty.push_back(bad);
      }
    }
    StrokeEngine clean_engine(config, 192, 128), dirty_engine(config, 192, 128);
    Footprint expected = paintStroke(&clean_engine, clean).footprint;
    StrokeResult got = paintStroke(&dirty_engine, dirty);
    EXPECT_EQ(got.footprint.values, expected.values) << brushKindName(kind);
    EXPECT_EQ(got.path.size(), clean.size());
    EXPECT_GT(dirty_engine.inputStats().dropped_non_finite, 10u);

    // Wild values inside a stroke are clamped: the footprint stays finite and in 0..1.
    StrokeEngine wild_engine(config, 192, 128);
    std::vector<BrushInput> wild = clean;
    for (size_t i = 2; i < wild.size(); i += 5) {
      wild[i].pressure = 50.0f;
      wild[i].tilt_x_deg = -kInf;
      wild[i].tilt_y_deg = 1e30f;
    }
    wild[wild.size() / 2].footprint_px = {1e12f, -1e12f};
    Footprint w = paintStroke(&wild_engine, wild).footprint;
    for (float v : w.values) ASSERT_TRUE(v >= 0.0f && v <= 1.0f) << brushKindName(kind);
    EXPECT_GT(wild_engine.inputStats().clamped_pressure, 5u);
    EXPECT_GT(wild_engine.inputStats().repaired_tilt, 5u);
    EXPECT_EQ(wild_engine.inputStats().clamped_position, 1u);
  }
}

// The engine never decides contact from pressure (the calibration's hysteresis does, once):
// explicit tip-down, moves and tip-up drive the stroke, whatever the pressure.
TEST(StrokeEngine, ExplicitContactStartsAndEndsStrokes) {
  BrushConfig config;
  config.default_brush = BrushKind::k2D;
  StrokeEngine engine(config, 128, 64);
  engine.setNextStrokeIndex(41);
  BrushInput hover{{20.0f, 30.0f}, 0.005f, 0.0f, 0.0f, 0};
  engine.prepareNextStroke();
  EXPECT_FALSE(engine.inStroke());
  BrushInput down = hover;
  down.pressure = 0.5f;
  down.t_ns = 5000000;
  EXPECT_FALSE(engine.beginStroke(down).empty());
  EXPECT_TRUE(engine.inStroke());
  BrushInput move = down;
  move.footprint_px.x = 60.0f;
  move.t_ns = 10000000;
  engine.addSample(move);
  BrushInput light = move;  // a light touch is still a touch: only the caller lifts the pen
  light.pressure = 0.005f;
  light.t_ns = 15000000;
  engine.addSample(light);
  EXPECT_TRUE(engine.inStroke());
  engine.finishStroke();
  EXPECT_FALSE(engine.inStroke());
  StrokeResult result;
  ASSERT_TRUE(engine.takeFinishedStroke(&result));
  EXPECT_EQ(result.stroke_index, 41u);
  EXPECT_EQ(result.brush, BrushKind::k2D);
  EXPECT_EQ(result.path.size(), 3u);
  EXPECT_EQ(result.footprint.width, 128);
  EXPECT_GT(inkedPixels(result.footprint), 50);
  EXPECT_FALSE(engine.takeFinishedStroke(&result));
  EXPECT_EQ(engine.nextStrokeIndex(), 42u);
}

TEST(StrokeEngine, CalibratedContactDrivesTheStrokeAndKeepsRawSamples) {
  BrushConfig config;
  config.default_brush = BrushKind::k3D;
  config.stroke.footprint_scale = 0.5f;  // footprint at half the screen resolution
  StrokeEngine engine(config, 200, 100);
  auto mapped = [](double x, float pressure, bool contact, int64_t t) {
    MappedSample m;
    m.t_ns = t;
    m.x_px = x;
    m.y_px = 100.0;
    m.pressure = pressure;
    m.contact = contact;
    m.raw.t_ns = t;
    m.raw.pressure_raw = int32_t(pressure * 1000);
    return m;
  };
  // Hovering: pressure alone never starts a stroke here, contact does.
  EXPECT_TRUE(engine.feedCalibrated(mapped(100, 0.3f, false, 0)).empty());
  EXPECT_FALSE(engine.inStroke());
  MappedSample down = mapped(100, 0.3f, true, 5000000);
  down.contact_began = true;
  FootprintRect r = engine.feedCalibrated(down);
  EXPECT_TRUE(engine.inStroke());
  EXPECT_FALSE(r.empty());
  EXPECT_LT(r.x0, 50);  // screen x 100 -> footprint x 50
  EXPECT_GT(r.x1, 50);
  for (int i = 1; i <= 10; ++i)
    engine.feedCalibrated(mapped(100 + 10 * i, 0.004f, true, 5000000 * (i + 1)));
  EXPECT_TRUE(engine.inStroke());  // low pressure but still in contact: the hysteresis decides
  MappedSample up = mapped(210, 0.0f, false, 60000000);
  up.contact_ended = true;
  engine.feedCalibrated(up);
  EXPECT_FALSE(engine.inStroke());
  StrokeResult result;
  ASSERT_TRUE(engine.takeFinishedStroke(&result));
  EXPECT_EQ(result.path.size(), 11u);
  ASSERT_EQ(result.raw_path.size(), 12u);  // the lifting sample is kept raw, not painted
  EXPECT_EQ(result.raw_path.back().t_ns, 60000000);
  EXPECT_FLOAT_EQ(result.path.back().footprint_px.x, 100.0f);
}

TEST(StrokeEngine, RejectsAnEmptyFootprintSize) {
  EXPECT_THROW(StrokeEngine(BrushConfig{}, 0, 10), std::invalid_argument);
}

}  // namespace
}  // namespace cb::test
