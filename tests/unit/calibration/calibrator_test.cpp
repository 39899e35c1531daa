#include "calibration/calibrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "calibration/point_fit.h"

namespace cb {
namespace {

PenDeviceInfo intuos4() {
  PenDeviceInfo d;
  d.usb_vendor = 0x056a;
  d.usb_product = 0x00b9;
  std::strcpy(d.name, "Wacom Intuos4 6x9 Pen");
  d.x_max = 44704;  // 223.52 mm at 200 units/mm
  d.y_max = 27940;  // 139.70 mm
  d.x_res = d.y_res = 200.0;
  d.pressure_max = 2047;
  d.tilt_min = -64;
  d.tilt_max = 63;
  d.distance_max = 63;
  return d;
}

PenSample sample(int64_t i, double x_mm, double y_mm, float pressure, bool prox = true) {
  PenSample s;
  s.t_ns = i * 5'000'000;
  s.x_mm = x_mm;
  s.y_mm = y_mm;
  s.pressure = pressure;
  s.in_proximity = prox;
  s.distance = pressure > 0.2f ? 0.0f : 0.6f;
  s.buttons = pressure > 0.02f ? uint32_t{kPenTip} : 0u;
  return s;
}

TEST(Calibrator, MapsCentreToCentreAndCornersToScreen) {
  CalibrationProfile p;
  p.area.fit = AreaFit::kStretch;
  Calibrator c(p, intuos4(), 1920, 1080);
  ASSERT_TRUE(c.ok()) << c.error();
  MappedSample m = c.process(sample(0, 223.52 / 2, 139.70 / 2, 0.0f));
  EXPECT_NEAR(m.x_px, 960.0, 1e-6);
  EXPECT_NEAR(m.y_px, 540.0, 1e-6);
  EXPECT_TRUE(m.proximity_began);
  EXPECT_EQ(m.raw.x_mm, 223.52 / 2);
}

TEST(Calibrator, StrokeLifecycleWithContactEdges) {
  Calibrator c(CalibrationProfile{}, intuos4(), 1920, 1080);
  int began = 0, ended = 0, down = 0;
  int64_t i = 0;
  for (; i < 20; ++i) c.process(sample(i, 100, 70, 0.0f));  // hover
  for (; i < 120; ++i) {
    MappedSample m = c.process(sample(i, 100 + (i - 20) * 0.5, 70, 0.5f));
    began += m.contact_began;
    down += m.contact;
    EXPECT_GT(m.pressure, 0.0f);
  }
  for (; i < 140; ++i) {
    MappedSample m = c.process(sample(i, 150, 70, 0.0f));
    ended += m.contact_ended;
    EXPECT_EQ(m.pressure, 0.0f);
  }
  MappedSample out = c.process(sample(i, 150, 70, 0.0f, /*prox=*/false));
  EXPECT_FALSE(out.contact);
  EXPECT_EQ(began, 1);
  EXPECT_EQ(ended, 1);
  EXPECT_EQ(down, 100);
}

TEST(Calibrator, ProximityOutWhileDownEndsTheStroke) {
  Calibrator c(CalibrationProfile{}, intuos4(), 1920, 1080);
  c.process(sample(0, 100, 70, 0.5f));
  MappedSample m = c.process(sample(1, 100, 70, 0.5f, false));
  EXPECT_TRUE(m.contact_ended);
  EXPECT_FALSE(m.contact);
}

TEST(Calibrator, TipDownResetsTheFilterSoTheStrokeStartsUnderThePen) {
  CalibrationProfile p;
  p.area.fit = AreaFit::kStretch;
  Calibrator c(p, intuos4(), 2235, 1397);  // 10 px per mm
  // Hover far away, then touch down 50 mm further right: the first contact sample is exact.
  for (int64_t i = 0; i < 40; ++i) c.process(sample(i, 50, 70, 0.0f));
  MappedSample m = c.process(sample(40, 100, 70, 0.5f));
  ASSERT_TRUE(m.contact_began);
  EXPECT_NEAR(m.x_px, applyTransform(c.tabletToScreen(), {100, 70}).x, 1e-9);
}

TEST(Calibrator, AppliesCorrectionAfterAreaMapping) {
  CalibrationProfile p;
  p.area.fit = AreaFit::kStretch;
  p.fit_kind = PointFitKind::kAffine;
  p.correction[2][0] = 12.0;  // shift 12 px right
  Calibrator c(p, intuos4(), 1920, 1080);
  MappedSample m = c.process(sample(0, 0, 0, 0.0f));
  EXPECT_NEAR(m.x_px, 12.0, 1e-9);
  EXPECT_NEAR(applyTransform(c.areaTransform(), {0, 0}).x, 0.0, 1e-9);
}

TEST(Calibrator, WornNibDoesNotPaintAndPressureCurveApplies) {
  CalibrationProfile p;
  p.pressure.curve = {0, 40, 60, 100};  // soft
  Calibrator c(p, intuos4(), 1920, 1080);
  PenSample s = sample(0, 100, 70, 0.1f);  // 10 % in the air, hovering high
  s.buttons = 0;
  s.distance = 0.8f;
  for (int64_t i = 0; i < 20; ++i) {
    s.t_ns = i * 5'000'000;
    EXPECT_FALSE(c.process(s).contact);
  }
  EXPECT_NEAR(c.nibOffset(), 0.1f, 1e-6);
  MappedSample m = c.process(sample(21, 100, 70, 0.55f));
  EXPECT_TRUE(m.contact);
  // (0.55 - 0.1) / 0.9 = 0.5 through a soft curve: well above 0.5.
  EXPECT_GT(m.pressure, 0.6f);
  c.setPressureRange(PressureRange{0.0f, 0.5f});
  m = c.process(sample(22, 100, 70, 0.55f));
  EXPECT_NEAR(m.pressure, 1.0f, 1e-6);
}

TEST(Calibrator, TiltZeroAndAngles) {
  CalibrationProfile p;
  p.tilt_zero = {2.0f, -1.0f};
  Calibrator c(p, intuos4(), 1920, 1080);
  PenSample s = sample(0, 100, 70, 0.3f);
  s.tilt_x_deg = 32.0f;
  s.tilt_y_deg = -1.0f;
  MappedSample m = c.process(s);
  EXPECT_NEAR(m.tilt_x_deg, 30.0f, 1e-5);
  EXPECT_NEAR(m.tilt_y_deg, 0.0f, 1e-5);
  EXPECT_NEAR(m.azimuth_deg, 0.0f, 1e-3);
  EXPECT_NEAR(m.altitude_deg, 60.0f, 1e-3);
}

TEST(Calibrator, BadSamplesAreHeldAndCounted) {
  Calibrator c(CalibrationProfile{}, intuos4(), 1920, 1080);
  MappedSample a = c.process(sample(0, 100, 70, 0.5f));
  PenSample bad = sample(1, NAN, 70, NAN);
  bad.tilt_x_deg = INFINITY;
  MappedSample b = c.process(bad);
  EXPECT_EQ(c.rejectedSamples(), 1u);
  EXPECT_TRUE(std::isfinite(b.x_px));
  EXPECT_NEAR(b.x_px, a.x_px, 1e-9);
  EXPECT_TRUE(std::isfinite(b.pressure));
  EXPECT_TRUE(std::isfinite(b.tilt_x_deg));
}

TEST(Calibrator, InvalidAreaFallsBackAndSaysWhy) {
  CalibrationProfile p;
  p.area.tablet_area_mm = RectD{0, 0, 500, 500};  // bigger than this tablet
  Calibrator c(p, intuos4(), 1920, 1080);
  EXPECT_FALSE(c.ok());
  EXPECT_NE(c.error().find("not inside"), std::string::npos);
  MappedSample m = c.process(sample(0, 223.52 / 2, 139.70 / 2, 0.0f));
  EXPECT_NEAR(m.x_px, 960.0, 1e-6);
}

TEST(Calibrator, DeterministicReplay) {
  std::vector<PenSample> trace;
  for (int64_t i = 0; i < 300; ++i) {
    trace.push_back(sample(i, 100 + 30 * std::sin(i * 0.05), 70 + 20 * std::cos(i * 0.03),
                           i > 50 && i < 250 ? 0.4f + 0.1f * std::sin(i * 0.1f) : 0.0f));
  }
  auto run = [&] {
    Calibrator c(CalibrationProfile{}, intuos4(), 1920, 1080);
    std::vector<MappedSample> out;
    for (const auto& s : trace) out.push_back(c.process(s));
    return out;
  };
  auto a = run(), b = run();
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].x_px, b[i].x_px);
    EXPECT_EQ(a[i].preview_y_px, b[i].preview_y_px);
    EXPECT_EQ(a[i].pressure, b[i].pressure);
  }
}

}  // namespace
}  // namespace cb
