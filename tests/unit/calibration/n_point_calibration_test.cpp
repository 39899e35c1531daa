#include "calibration/n_point_calibration.h"

#include <gtest/gtest.h>

#include <cmath>

#include "calibration/calibrator.h"
#include "calibration/point_fit.h"

namespace cb {
namespace {

PenDeviceInfo tablet() {
  PenDeviceInfo d;
  d.usb_vendor = 0x056a;
  d.usb_product = 0x00b9;
  d.x_max = 22352;
  d.y_max = 13970;
  d.x_res = d.y_res = 100.0;
  d.pressure_max = 2047;
  return d;
}

PenSample at(int64_t i, double x, double y, float p) {
  PenSample s;
  s.t_ns = i * 5'000'000;
  s.x_mm = x;
  s.y_mm = y;
  s.pressure = p;
  s.in_proximity = true;
  return s;
}

TEST(NPointCalibration, LayoutsCoverCornersAndCentre) {
  auto five = targetLayout(5, 1000, 500);
  ASSERT_EQ(five.size(), 5u);
  EXPECT_EQ(five[0], glm::dvec2(100, 50));
  EXPECT_EQ(five[2], glm::dvec2(900, 450));
  EXPECT_EQ(five[4], glm::dvec2(500, 250));
  auto nine = targetLayout(9, 1000, 500);
  ASSERT_EQ(nine.size(), 9u);
  EXPECT_EQ(nine[4], glm::dvec2(500, 250));
}

TEST(NPointCalibration, TapCollectorTakesMedianOfContact) {
  TapCollector c;
  EXPECT_FALSE(c.up()) << "no tap without a down";
  // Touch down with a slip at the start, hold, lift.
  c.down({51.5, 40});
  EXPECT_TRUE(c.inContact());
  for (int k = 0; k < 8; ++k) c.move({50 + 0.01 * k, 40});
  auto tap = c.up();
  ASSERT_TRUE(tap);
  EXPECT_FALSE(c.inContact());
  EXPECT_NEAR(tap->x, 50.04, 0.011);
  EXPECT_NEAR(tap->y, 40.0, 1e-9);
}

TEST(NPointCalibration, TapCollectorRefusesDragsAndFlickers) {
  TapCollector c;
  c.down({50, 40});
  for (int k = 1; k < 20; ++k) c.move({50.0 + k, 40});
  EXPECT_FALSE(c.up());
  EXPECT_NE(c.lastRejection().find("moved"), std::string::npos);
  c.down({50, 40});
  EXPECT_FALSE(c.up());
  EXPECT_NE(c.lastRejection().find("too short"), std::string::npos);
  // Positions that are not finite are left out; moves while up are ignored.
  c.move({60, 30});
  c.down({60, 30});
  c.move({std::nan(""), 30});
  for (int k = 0; k < 3; ++k) c.move({60, 30});
  auto tap = c.up();
  ASSERT_TRUE(tap) << c.lastRejection();
  EXPECT_EQ(*tap, glm::dvec2(60, 30));
}

TEST(NPointCalibration, FitRecoversMountingErrorAndCalibratorAppliesIt) {
  // A display tablet whose sensor sits 1.5 mm off and 0.4° turned against the panel.
  CalibrationProfile base;
  base.area.fit = AreaFit::kDisplay;
  const int w = 1920, h = 1200;
  const PenDeviceInfo dev = tablet();
  const double px_per_mm_x = w / 223.52, px_per_mm_y = h / 139.70;
  const double a = 0.4 * M_PI / 180;
  std::vector<Tap> taps;
  for (const glm::dvec2& t : targetLayout(9, w, h)) {
    const glm::dvec2 mm_true(t.x / px_per_mm_x, t.y / px_per_mm_y);
    const glm::dvec2 c(111.76, 69.85);
    const glm::dvec2 d = mm_true - c;
    const glm::dvec2 seen =
        c +
        glm::dvec2(std::cos(a) * d.x - std::sin(a) * d.y, std::sin(a) * d.x + std::cos(a) * d.y) +
        glm::dvec2(1.5, -0.7);
    taps.push_back({t, seen});
  }
  CalibrationFit fit = fitCalibration(base, dev, 0x77, w, h, taps, PointFitKind::kHomography);
  ASSERT_TRUE(fit.ok) << fit.error;
  EXPECT_LT(fit.fit.max_residual, 0.5);
  EXPECT_EQ(fit.profile.device.usb_product, 0x00b9);
  EXPECT_EQ(fit.profile.device.tool_serial, 0x77u);
  EXPECT_EQ(fit.profile.fit_points, 9);
  // The calibrator with this profile puts a tap exactly on its target.
  Calibrator cal(fit.profile, dev, w, h);
  MappedSample m = cal.process(at(0, taps[0].pen_mm.x, taps[0].pen_mm.y, 0.5f));
  EXPECT_NEAR(m.x_px, taps[0].target_px.x, 0.5);
  EXPECT_NEAR(m.y_px, taps[0].target_px.y, 0.5);
  // Without the correction it is several pixels off.
  Calibrator uncorrected(base, dev, w, h);
  MappedSample u = uncorrected.process(at(0, taps[0].pen_mm.x, taps[0].pen_mm.y, 0.5f));
  EXPECT_GT(std::hypot(u.x_px - taps[0].target_px.x, u.y_px - taps[0].target_px.y), 5.0);
}

TEST(NPointCalibration, TapFileParsesAndReportsLines) {
  const std::string good =
      "[screen]\nwidth = 1920\nheight = 1080\n"
      "[device]\nusb_vendor = 0x056a\nusb_product = 0x00b9\nwidth_mm = 223.52\nheight_mm = 139.7\n"
      "[[tap]]\ntarget_px = [192, 108]\npen_mm = [22.3, 14.0]\n"
      "[[tap]]\ntarget_px = [1728, 972]\npen_mm = [201.2, 125.7]\n";
  std::string err;
  auto f = parseTapFile(good, "taps.toml", &err);
  ASSERT_TRUE(f) << err;
  EXPECT_EQ(f->screen_w, 1920);
  EXPECT_EQ(f->device.x_max, 22352);
  ASSERT_EQ(f->taps.size(), 2u);
  EXPECT_EQ(f->taps[1].pen_mm.x, 201.2);
  EXPECT_FALSE(parseTapFile(good + "[[tap]]\ntarget_px = [1, 2]\n", "taps.toml", &err));
  EXPECT_NE(err.find("taps.toml:15:"), std::string::npos) << err;
  EXPECT_FALSE(parseTapFile("[screen]\nwidth = 1920\nheight = = 3\n", "t.toml", &err));
  EXPECT_NE(err.find("t.toml:3:"), std::string::npos) << err;
}

// Numbers toml++ would convert to an integer before checking (1e40 into int64_t is undefined):
// each is refused at its own line, naming the field.
TEST(NPointCalibration, TapFileRefusesNumbersOutOfRange) {
  const std::string device =
      "[device]\nusb_vendor = 0x056a\nusb_product = 0x00b9\nwidth_mm = 223.52\n"
      "height_mm = 139.7\n[[tap]]\ntarget_px = [192, 108]\npen_mm = [22.3, 14.0]\n";
  const struct {
    const char* screen;
    const char* want;
  } cases[] = {
      {"[screen]\nwidth = 1920\nheight = 1e40\n", "t.toml:3: screen.height: outside 1..65536"},
      {"[screen]\nwidth = -1\nheight = 1080\n", "t.toml:2: screen.width: -1 is outside 1..65536"},
      {"[screen]\nwidth = nan\nheight = 1080\n",
       "t.toml:2: screen.width: expected an integer in 1..65536"},
      {"[screen]\nwidth = 9223372036854775808.0\nheight = 1080\n",
       "t.toml:2: screen.width: outside 1..65536"},
  };
  for (const auto& c : cases) {
    std::string err;
    EXPECT_FALSE(parseTapFile(std::string(c.screen) + device, "t.toml", &err)) << c.screen;
    EXPECT_EQ(err, c.want);
  }
  std::string err;
  EXPECT_FALSE(
      parseTapFile("[screen]\nwidth = 1920\nheight = 1080\n"
                   "[device]\nusb_vendor = 0x056a\nusb_product = 0x00b9\n"
                   "width_mm = nan\nheight_mm = 139.7\n",
                   "t.toml", &err));
  EXPECT_EQ(err.rfind("t.toml:7: device.width_mm: ", 0), 0u) << err;
}

}  // namespace
}  // namespace cb
