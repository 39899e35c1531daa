#include "calibration/calibration_profile.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace cb {
namespace {

CalibrationProfile unusualProfile() {
  CalibrationProfile p;
  p.device.usb_vendor = 0x056a;
  p.device.usb_product = 0x00b9;
  p.device.tool_serial = 0x12345678;
  p.device.name = "Wacom Intuos4 \"M\" \\ test";
  p.area.fit = AreaFit::kLetterbox;
  p.area.tablet_area_mm = RectD{1.25, 2.5, 100.1, 60.3};
  p.area.screen_region_px = RectD{1920, 0, 1280, 720};
  p.area.rotation_deg = -17.3;
  p.fit_kind = PointFitKind::kHomography;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      p.correction[c][r] = (c == r ? 1.0 : 0.0) + 0.001 * (c * 3 + r) / 7.0;
  p.fit_rms_px = 0.123456789;
  p.fit_max_px = 0.3;
  p.fit_points = 9;
  p.pressure.curve = {0, 15.5, 85, 100};
  p.pressure.contact = {0.07f, 0.02f};
  p.pressure.nib = {0.4f, 0.15f};
  p.pressure.light_target = 0.25f;
  p.tilt_zero = {1.5f, -2.25f};
  p.smoothing.position = {1.7, 0.13, 3.3};
  p.smoothing.tilt = {0.9, 0.011, 1.1};
  p.prediction = {12.5, 25.0, false, 8.0};
  return p;
}

TEST(CalibrationProfile, RoundTripsExactly) {
  for (const CalibrationProfile& p : {CalibrationProfile{}, unusualProfile()}) {
    const std::string text = formatCalibrationProfile(p);
    ProfileParseResult r = parseCalibrationProfile(text, "roundtrip.toml");
    ASSERT_TRUE(r.profile) << (r.errors.empty() ? "" : r.errors[0]) << "\n" << text;
    EXPECT_TRUE(r.warnings.empty());
    EXPECT_TRUE(*r.profile == p) << text;
    // And the text is stable: formatting the parsed profile gives the same bytes.
    EXPECT_EQ(formatCalibrationProfile(*r.profile), text);
  }
}

TEST(CalibrationProfile, ShippedDefaultsParseCleanly) {
  const std::string path = std::string(CB_SOURCE_DIR) + "/config/calibration.toml";
  ProfileParseResult r = readCalibrationProfile(path);
  ASSERT_TRUE(r.profile) << (r.errors.empty() ? "" : r.errors[0]);
  EXPECT_TRUE(r.warnings.empty()) << r.warnings[0];
  EXPECT_TRUE(r.profile->device.anyDevice());
  // The shipped file states the built-in defaults (one source of truth each way).
  EXPECT_TRUE(*r.profile == CalibrationProfile{}) << formatCalibrationProfile(*r.profile);
}

TEST(CalibrationProfile, SyntaxErrorReportsFileAndLine) {
  const std::string text = "[area]\nfit = \"fit\"\n\n[pressure]\ncurve = [0, 0, 100\n";
  ProfileParseResult r = parseCalibrationProfile(text, "/tmp/broken.toml");
  EXPECT_FALSE(r.profile);
  ASSERT_FALSE(r.errors.empty());
  EXPECT_EQ(r.errors[0].rfind("/tmp/broken.toml:5:", 0), 0u) << r.errors[0];
}

TEST(CalibrationProfile, BadValuesReportFileLineAndKey) {
  const std::string text =
      "[area]\n"
      "fit = \"zoom\"\n"  // 2
      "[pressure]\n"
      "curve = [0, 150, 100, 100]\n"  // 4
      "contact_down = \"high\"\n"     // 5
      "[smoothing.position]\n"
      "beta = -1\n"  // 7
      "[fit]\n"
      "matrix = [0,0,0, 0,0,0, 0,0,0]\n"  // 9
      "[device]\n"
      "usb_vendor = 70000\n";  // 11
  ProfileParseResult r = parseCalibrationProfile(text, "kiosk.toml");
  EXPECT_FALSE(r.profile);
  const std::vector<std::string> want = {"kiosk.toml:2:", "kiosk.toml:4:", "kiosk.toml:5:",
                                         "kiosk.toml:7:", "kiosk.toml:9:", "kiosk.toml:11:"};
  std::string all;
  for (const auto& e : r.errors) all += e + "\n";
  for (const auto& w : want) EXPECT_NE(all.find(w), std::string::npos) << w << " in\n" << all;
  EXPECT_NE(all.find("area.fit"), std::string::npos);
  EXPECT_NE(all.find("y1"), std::string::npos);
  EXPECT_NE(all.find("smoothing.position.beta"), std::string::npos);
  EXPECT_NE(all.find("singular"), std::string::npos);
}

TEST(CalibrationProfile, UnknownKeysWarnButLoad) {
  ProfileParseResult r = parseCalibrationProfile(
      "[pressure]\ncurve = [0, 10, 90, 100]\nwobble = 3\n[future]\nx = 1\n", "p.toml");
  ASSERT_TRUE(r.profile);
  EXPECT_EQ(r.warnings.size(), 2u);
  EXPECT_NE(r.warnings[0].find("p.toml:3: unknown key pressure.wobble"), std::string::npos)
      << r.warnings[0];
  EXPECT_EQ(r.profile->pressure.curve[1], 10.0);
}

TEST(CalibrationProfile, DeviceMatching) {
  PenDeviceInfo intuos;
  intuos.usb_vendor = 0x056a;
  intuos.usb_product = 0x00b9;
  PenDeviceInfo other = intuos;
  other.usb_product = 0x0357;
  DeviceMatch any;
  EXPECT_TRUE(any.matches(intuos, 0));
  EXPECT_TRUE(any.matches(other, 99));
  DeviceMatch m;
  m.usb_vendor = 0x056a;
  m.usb_product = 0x00b9;
  EXPECT_TRUE(m.matches(intuos, 0));
  EXPECT_TRUE(m.matches(intuos, 1234));
  EXPECT_FALSE(m.matches(other, 0));
  m.tool_serial = 1234;
  EXPECT_TRUE(m.matches(intuos, 1234));
  EXPECT_FALSE(m.matches(intuos, 4321));
  EXPECT_EQ(m.describe(), "056a:00b9 tool serial 0x4d2");
}

}  // namespace
}  // namespace cb
