// `cloudbrush calibrate` end to end: the interactive loop driven by a replayed pen (the replay
// backend) on the surfaceless display (EGL on llvmpipe), then the non-interactive paths
// (--journal re-fit of the recorded session, --points tap file) and their error reports.
#include <gtest/gtest.h>
#include <png.h>

#include <unistd.h>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "calibration/area_mapping.h"
#include "calibration/calibration_profile.h"
#include "calibration/n_point_calibration.h"
#include "calibration/point_fit.h"
#include "calibration/pressure_range.h"
#include "drivers/core/journal.h"

namespace cb {
namespace {

namespace fs = std::filesystem;

constexpr int kW = 1280, kH = 720;  // the surfaceless display's default size

PenDeviceInfo intuos4() {
  PenDeviceInfo d;
  d.usb_vendor = 0x056a;
  d.usb_product = 0x00b9;
  std::strcpy(d.name, "Wacom Intuos4 6x9 Pen");
  d.x_max = 44704;
  d.y_max = 27940;
  d.x_res = d.y_res = 200.0;
  d.pressure_max = 2047;
  d.tilt_min = -64;
  d.tilt_max = 63;
  d.distance_max = 63;
  return d;
}

// The tablet's error the calibration has to find, in screen px: a small perspective tilt.
glm::dmat3 distortion() {
  glm::dmat3 m(1.0);
  m[0][0] = 1.01;
  m[1][0] = 0.004;
  m[2][0] = -6.0;
  m[0][1] = -0.003;
  m[1][1] = 0.995;
  m[2][1] = 4.0;
  m[0][2] = 1e-6;
  return m;
}

bool readPngRgba(const std::string& path, std::vector<uint8_t>* rgba, int* w, int* h) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) return false;
  image.format = PNG_FORMAT_RGBA;
  rgba->resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, rgba->data(), 0, nullptr)) return false;
  *w = static_cast<int>(image.width);
  *h = static_cast<int>(image.height);
  return true;
}

std::string run(const std::string& cmd, int* status) {
  const std::string out =
      (fs::temp_directory_path() / ("cb_calibrate_cmd_out_" + std::to_string(::getpid()) + ".txt"))
          .string();
  *status = std::system((cmd + " > " + out + " 2>&1").c_str());
  std::ifstream in(out);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class CalibrateCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("cb_calibrate_cmd_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "config");
    // Shipped defaults as they are in the tree.
    fs::copy_file(fs::path(CB_SOURCE_DIR) / "config/calibration.toml",
                  root_ / "config/calibration.toml");
  }
  void TearDown() override {
    if (!std::getenv("CB_KEEP_TEST_FILES")) fs::remove_all(root_);
  }

  // A calibration session as the replay backend plays it: hover, then a tap on every target
  // where the distorted tablet reports it.
  // What the pen does in a session: tap every target (as a tablet with `error` reports them),
  // or tap a point given in screen px under the area mapping alone (the result screen's boxes).
  struct Action {
    enum Kind { kTapTargets, kTapScreen } kind;
    glm::dmat3 error{1.0};
    glm::dvec2 screen_px{0.0};
  };

  // A calibration session as the replay backend plays it.
  std::string writeSessionJournal(const std::vector<Action>& actions) {
    const PenDeviceInfo dev = intuos4();
    ProfileParseResult defaults =
        readCalibrationProfile((root_ / "config/calibration.toml").string());
    EXPECT_TRUE(defaults.profile);
    const AreaMapping area = computeAreaMapping(defaults.profile->area, 223.52, 139.70, kW, kH);
    EXPECT_TRUE(area.ok);
    const std::string path = (root_ / "session.cbj").string();
    JournalWriter w;
    EXPECT_TRUE(w.open(path)) << w.error();
    const auto dev_bytes = encodeDeviceInfo(dev);
    w.append(JournalRecordType::kDevice, 0, dev_bytes.data(), dev_bytes.size());
    int64_t t = 1'000'000'000;
    auto emit = [&](glm::dvec2 mm, float pressure, float distance) {
      PenSample s;
      s.t_ns = t;
      t += 5'000'000;
      s.x_mm = mm.x;
      s.y_mm = mm.y;
      s.x_raw = static_cast<int32_t>(std::lround(mm.x * 200));
      s.y_raw = static_cast<int32_t>(std::lround(mm.y * 200));
      s.pressure = pressure;
      s.pressure_raw = static_cast<int32_t>(pressure * 2047);
      s.distance = distance;
      s.buttons = pressure > 0.01f ? uint32_t{kPenTip} : 0u;
      s.tool = PenTool::kPen;
      s.tool_serial = 0x1234;
      s.in_proximity = true;
      w.appendPenSample(s);
    };
    auto tap = [&](glm::dvec2 mm) {
      for (int i = 0; i < 10; ++i) emit(mm + glm::dvec2(0, -3.0 + 0.3 * i), 0.0f, 0.6f);
      for (int i = 0; i < 12; ++i) emit(mm, 0.4f, 0.0f);
      for (int i = 0; i < 10; ++i) emit(mm + glm::dvec2(0, 0.3 * i), 0.0f, 0.6f);
    };
    for (const Action& a : actions) {
      if (a.kind == Action::kTapScreen) {
        tap(applyTransform(glm::inverse(area.tablet_to_screen), a.screen_px));
        continue;
      }
      // Where the pen must be so that area mapping then the error lands on the target:
      // error(area(mm)) = target  =>  mm = area^-1(error^-1(target)).
      const glm::dmat3 to_mm = glm::inverse(area.tablet_to_screen) * glm::inverse(a.error);
      for (const glm::dvec2& target : targetLayout(9, kW, kH)) tap(applyTransform(to_mm, target));
    }
    w.close();
    return path;
  }

  fs::path root_;
};

TEST_F(CalibrateCommandTest, InteractiveLoopWithReplayedPenSavesProfileAndJournalRefits) {
  const std::string session = writeSessionJournal({{Action::kTapTargets, distortion()}});
  const std::string state = (root_ / "state").string();
  const std::string record = (root_ / "record.cbj").string();
  const std::string snapshot = (root_ / "result.png").string();
  int status = 0;
  std::string out = run(std::string(CB_CLOUDBRUSH_BIN) + " calibrate --backend replay --device " +
                            session + " --display surfaceless --yes --timeout 120 --config-dir " +
                            (root_ / "config").string() + " --state-dir " + state + " --record " +
                            record + " --snapshot " + snapshot,
                        &status);
  ASSERT_EQ(status, 0) << out;

  // The result screen really was drawn (EGL surfaceless on llvmpipe): accept box green, redo
  // box orange, target crosshairs light grey, background dark.
  std::vector<uint8_t> rgba;
  int sw = 0, sh = 0;
  ASSERT_TRUE(readPngRgba(snapshot, &rgba, &sw, &sh)) << out;
  if (const char* keep = std::getenv("CB_KEEP_FRAMES"))  // for looking at it
    std::filesystem::copy_file(snapshot, std::string(keep) + "/calibrate_result.png",
                               std::filesystem::copy_options::overwrite_existing);
  ASSERT_EQ(sw, kW);
  ASSERT_EQ(sh, kH);
  auto px = [&](int x, int y) { return &rgba[(static_cast<size_t>(y) * sw + x) * 4]; };
  EXPECT_EQ(px(3 * kW / 10, 7 * kH / 10)[1], 166);  // accept: (0.2, 0.65, 0.25)
  EXPECT_GT(px(3 * kW / 10, 7 * kH / 10)[1], px(3 * kW / 10, 7 * kH / 10)[0]);
  EXPECT_EQ(px(7 * kW / 10, 7 * kH / 10)[0], 230);  // redo: (0.9, 0.5, 0.1)
  const glm::dvec2 t0 = targetLayout(9, kW, kH)[0];
  EXPECT_EQ(px(static_cast<int>(t0.x) + 8, static_cast<int>(t0.y))[0], 204);  // crosshair arm
  EXPECT_LT(px(5, kH - 5)[0], 40);                                            // background
  EXPECT_NE(out.find("homography fit over 9 points"), std::string::npos) << out;

  const std::string saved = state + "/profiles/056a-00b9.toml";
  ProfileParseResult r = readCalibrationProfile(saved);
  ASSERT_TRUE(r.profile) << out;
  EXPECT_EQ(r.profile->device.usb_vendor, 0x056a);
  EXPECT_EQ(r.profile->device.usb_product, 0x00b9);
  EXPECT_EQ(r.profile->fit_kind, PointFitKind::kHomography);
  EXPECT_LT(r.profile->fit_max_px, 0.5);
  // The taps were made so that the area mapping alone lands them on distortion^-1(target):
  // the fitted correction is the distortion itself, over the whole screen.
  for (const glm::dvec2& p : targetLayout(9, kW, kH, 0.0)) {
    const glm::dvec2 d = applyTransform(r.profile->correction, p) - applyTransform(distortion(), p);
    EXPECT_LT(glm::length(d), 0.5) << p.x << "," << p.y;
  }

  // The recorded session re-fits to the same profile without pen or display.
  const std::string state2 = (root_ / "state2").string();
  out = run(std::string(CB_CLOUDBRUSH_BIN) + " calibrate --journal " + record +
                " --save --config-dir " + (root_ / "config").string() + " --state-dir " + state2,
            &status);
  ASSERT_EQ(status, 0) << out;
  ProfileParseResult again = readCalibrationProfile(state2 + "/profiles/056a-00b9.toml");
  ASSERT_TRUE(again.profile) << out;
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(again.profile->correction[c][k], r.profile->correction[c][k], 1e-9);
}

TEST_F(CalibrateCommandTest, RedoThenAcceptWithThePen) {
  // First round with a skewed tablet, the orange box (redo), a second round with a shifted
  // tablet, the green box (accept): the saved correction is the second round's.
  glm::dmat3 shift(1.0);
  shift[2][0] = 9.0;
  shift[2][1] = -5.0;
  const std::string session = writeSessionJournal({{Action::kTapTargets, distortion()},
                                                   {Action::kTapScreen, {}, {0.7 * kW, 0.7 * kH}},
                                                   {Action::kTapTargets, shift},
                                                   {Action::kTapScreen, {}, {0.3 * kW, 0.7 * kH}}});
  const std::string state = (root_ / "state").string();
  int status = 0;
  std::string out =
      run(std::string(CB_CLOUDBRUSH_BIN) + " calibrate --backend replay --device " + session +
              " --display surfaceless --timeout 120 --config-dir " + (root_ / "config").string() +
              " --state-dir " + state + " --record " + (root_ / "record.cbj").string(),
          &status);
  ASSERT_EQ(status, 0) << out;
  EXPECT_NE(out.find("redo"), std::string::npos) << out;
  ProfileParseResult r = readCalibrationProfile(state + "/profiles/056a-00b9.toml");
  ASSERT_TRUE(r.profile) << out;
  for (const glm::dvec2& p : targetLayout(9, kW, kH, 0.0)) {
    const glm::dvec2 d = applyTransform(r.profile->correction, p) - applyTransform(shift, p);
    EXPECT_LT(glm::length(d), 0.5) << p.x << "," << p.y;
  }
  // The re-fit of the record follows the redo marker to the same answer.
  out = run(std::string(CB_CLOUDBRUSH_BIN) + " calibrate --journal " +
                (root_ / "record.cbj").string() + " --config-dir " + (root_ / "config").string() +
                " --state-dir " + (root_ / "state2").string() + " --save",
            &status);
  ASSERT_EQ(status, 0) << out;
  ProfileParseResult again =
      readCalibrationProfile((root_ / "state2/profiles/056a-00b9.toml").string());
  ASSERT_TRUE(again.profile) << out;
  EXPECT_NEAR(again.profile->correction[2][0], r.profile->correction[2][0], 1e-9);
}

TEST_F(CalibrateCommandTest, PressureCalibrationFromReplayedPresses) {
  const std::string path = (root_ / "presses.cbj").string();
  JournalWriter w;
  ASSERT_TRUE(w.open(path)) << w.error();
  const auto dev_bytes = encodeDeviceInfo(intuos4());
  w.append(JournalRecordType::kDevice, 0, dev_bytes.data(), dev_bytes.size());
  int64_t t = 1'000'000'000;
  auto emit = [&](float pressure, int n) {
    for (int i = 0; i < n; ++i) {
      PenSample s;
      s.t_ns = (t += 5'000'000);
      s.x_mm = 100;
      s.y_mm = 70;
      s.pressure = pressure > 0 ? pressure + 0.004f * ((i % 5) - 2) : 0.0f;
      s.distance = pressure > 0 ? 0.0f : 0.7f;
      s.buttons = pressure > 0 ? uint32_t{kPenTip} : 0u;
      s.in_proximity = true;
      w.appendPenSample(s);
    }
  };
  emit(0.0f, 20);
  emit(0.15f, 120);  // light
  emit(0.0f, 20);
  emit(0.55f, 120);  // firm
  emit(0.0f, 20);
  w.close();
  const std::string session = (root_ / "session.toml").string();
  int status = 0;
  std::string out =
      run(std::string(CB_CLOUDBRUSH_BIN) + " calibrate --pressure --backend replay --device " +
              path + " --display surfaceless --timeout 60 --session-out " + session + " --record " +
              (root_ / "presses_record.cbj").string() + " --config-dir " +
              (root_ / "config").string() + " --state-dir " + (root_ / "s").string(),
          &status);
  ASSERT_EQ(status, 0) << out;
  std::ifstream in(session);
  std::stringstream ss;
  ss << in.rdbuf();
  std::string err;
  auto range = pressureRangeFromToml(ss.str(), &err);
  ASSERT_TRUE(range) << err << "\n" << out;
  EXPECT_NEAR(range->hi, 0.555f, 0.01f);
  EXPECT_NEAR(range->apply(0.15f), 0.2f, 0.02f);  // the light press gives the light target
  // The record ends with the session's pressure range.
  JournalReadResult rec = readJournal((root_ / "presses_record.cbj").string());
  ASSERT_TRUE(rec.error.empty()) << rec.error;
  ASSERT_FALSE(rec.records.empty());
  EXPECT_EQ(rec.records.back().type, JournalRecordType::kSession);
  EXPECT_EQ(rec.records.back().text(), ss.str());
}

TEST_F(CalibrateCommandTest, PointsFileFitsAndBadFileNamesLine) {
  const fs::path taps = root_ / "taps.toml";
  std::ofstream(taps) << "[screen]\nwidth = 1000\nheight = 1000\n"
                         "[device]\nusb_vendor = 0x056a\nusb_product = 0x00b9\n"
                         "width_mm = 100\nheight_mm = 100\n"
                         "[[tap]]\ntarget_px = [100, 100]\npen_mm = [10.2, 10.1]\n"
                         "[[tap]]\ntarget_px = [900, 100]\npen_mm = [90.2, 10.1]\n"
                         "[[tap]]\ntarget_px = [900, 900]\npen_mm = [90.2, 90.1]\n"
                         "[[tap]]\ntarget_px = [100, 900]\npen_mm = [10.2, 90.1]\n"
                         "[[tap]]\ntarget_px = [500, 500]\npen_mm = [50.2, 50.1]\n";
  int status = 0;
  std::string out = run(std::string(CB_CLOUDBRUSH_BIN) + " calibrate --points " + taps.string() +
                            " --fit affine --config-dir " + (root_ / "config").string() +
                            " --state-dir " + (root_ / "s").string(),
                        &status);
  ASSERT_EQ(status, 0) << out;
  EXPECT_NE(out.find("affine fit over 5 points"), std::string::npos) << out;
  EXPECT_NE(out.find("max 0.000 px"), std::string::npos) << out;
  EXPECT_FALSE(fs::exists(root_ / "s/profiles"));  // no --save

  std::ofstream(taps) << "[screen]\nwidth = 1000\nheight = 1000\n[device]\nusb_vendor = \n";
  out = run(std::string(CB_CLOUDBRUSH_BIN) + " calibrate --points " + taps.string(), &status);
  EXPECT_NE(status, 0);
  EXPECT_NE(out.find(taps.string() + ":5:"), std::string::npos) << out;
}

TEST_F(CalibrateCommandTest, BadOptionsSayWhat) {
  int status = 0;
  std::string out = run(std::string(CB_CLOUDBRUSH_BIN) + " calibrate --targets 7", &status);
  EXPECT_NE(status, 0);
  EXPECT_NE(out.find("--targets must be 5 or 9"), std::string::npos) << out;
  out = run(std::string(CB_CLOUDBRUSH_BIN) + " calibrate --fitt affine", &status);
  EXPECT_NE(out.find("unknown option --fitt"), std::string::npos) << out;
  out = run(std::string(CB_CLOUDBRUSH_BIN) + " calibrate --journal /nonexistent.cbj", &status);
  EXPECT_NE(status, 0);
  EXPECT_NE(out.find("/nonexistent.cbj"), std::string::npos) << out;
}

}  // namespace
}  // namespace cb
