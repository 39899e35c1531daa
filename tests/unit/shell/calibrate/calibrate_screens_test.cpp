// The calibration screens through the shell's one frame loop on the surfaceless display (EGL on
// llvmpipe), driven by scripted pen samples played by the replay pen source: wait for the pen,
// the targets, the result with its residuals, a redo and an accept with pen taps on the boxes,
// the saved profile; the participant's light and firm press; Esc cancelling a pushed flow.
// CB_KEEP_FRAMES=DIR keeps the first frame of every screen for looking.
#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>

#include "app/render/image_io.h"
#include "app/shell/calibrate/calibrate_flow_screen.h"
#include "app/shell/calibrate/calibrate_result_screen.h"
#include "app/shell/frame_loop.h"
#include "app/shell/keymap.h"
#include "calibration/area_mapping.h"
#include "calibration/profile_store.h"
#include "drivers/core/journal.h"
#include "drivers/evdev/evdev_pen_source.h"
#include "drivers/replay/replay_pen_source.h"
#include "tests/support/test_display.h"

namespace cb {
namespace {

namespace fs = std::filesystem;

constexpr int kW = 960, kH = 540;

PenDeviceInfo intuos4() {
  PenDeviceInfo d;
  d.usb_vendor = 0x056a;
  d.usb_product = 0x00b9;
  std::strcpy(d.name, "Wacom Intuos4 6x9 Pen");
  d.x_max = 44704;
  d.y_max = 27940;
  d.x_res = d.y_res = 200.0;
  d.pressure_max = 2047;
  d.distance_max = 63;
  return d;
}

// A tablet whose reports are off by a small perspective tilt, in screen px.
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

glm::dmat3 shift() {
  glm::dmat3 m(1.0);
  m[2][0] = 9.0;
  m[2][1] = -5.0;
  return m;
}

class CalibrateScreensTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("cb_calibrate_screens_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "config");
    fs::copy_file(fs::path(CB_SOURCE_DIR) / "config/calibration.toml",
                  root_ / "config/calibration.toml");
    std::string error;
    display_ = test::openTestDisplay(kW, kH, &error);
    ASSERT_TRUE(display_) << error;
    ProfileParseResult defaults =
        readCalibrationProfile((root_ / "config/calibration.toml").string());
    ASSERT_TRUE(defaults.profile);
    area_ = computeAreaMapping(defaults.profile->area, 223.52, 139.70, kW, kH).tablet_to_screen;
  }
  void TearDown() override { fs::remove_all(root_); }

  // Scripted pen samples, written as a journal for the replay pen source.
  struct Script {
    JournalWriter w;
    int64_t t = 1'000'000'000;
    void emit(glm::dvec2 mm, float pressure, float distance) {
      PenSample s;
      s.t_ns = (t += 5'000'000);
      s.x_mm = mm.x;
      s.y_mm = mm.y;
      s.pressure = pressure;
      s.distance = distance;
      s.buttons = pressure > 0.01f ? uint32_t{kPenTip} : 0u;
      s.tool = PenTool::kPen;
      s.tool_serial = 0x1234;
      s.in_proximity = true;
      w.appendPenSample(s);
    }
    // Hover in from above, touch for 60 ms, hover away.
    void tap(glm::dvec2 mm) {
      for (int i = 0; i < 10; ++i) emit(mm + glm::dvec2(0, -3.0 + 0.3 * i), 0.0f, 0.6f);
      for (int i = 0; i < 12; ++i) emit(mm, 0.4f, 0.0f);
      for (int i = 0; i < 10; ++i) emit(mm + glm::dvec2(0, 0.3 * i), 0.0f, 0.6f);
    }
  };
  std::string open(Script* s, const std::string& name) {
    const std::string path = (root_ / name).string();
    EXPECT_TRUE(s->w.open(path)) << s->w.error();
    const auto bytes = encodeDeviceInfo(intuos4());
    s->w.append(JournalRecordType::kDevice, 0, bytes.data(), bytes.size());
    return path;
  }
  // The pen at `mm` lands, by the area mapping and the tablet's error, on `screen_px`.
  glm::dvec2 mmFor(glm::dvec2 screen_px, const glm::dmat3& error) const {
    return applyTransform(glm::inverse(area_) * glm::inverse(error), screen_px);
  }

  // Runs `flow` on the frame loop until it ends; keeps the first frame of every stage.
  struct Seen {
    std::vector<CalibrateFlowScreen::Stage> stages;  // in order, each change once
    std::map<int, ImageRgba8> first_frame;           // by stage (first time it was drawn)
  };
  FrameLoopResult run(CalibrateFlowScreen& flow, PenSource* pen, Seen* seen,
                      const std::string& keys = "", long max_frames = 0) {
    FrameLoopOptions options;
    options.max_seconds = 60.0;
    options.max_frames = max_frames;
    std::string error;
    if (!keys.empty()) {
      EXPECT_TRUE(parseKeyList(keys, &options.initial_keys, &error)) << error;
    }
    int round = 0;
    options.after_draw = [&](const FrameContext& frame) {
      const CalibrateFlowScreen::Stage stage = flow.stage();
      if (!seen->stages.empty() && seen->stages.back() == stage) return;
      seen->stages.push_back(stage);
      ImageRgba8 rgba =
          readFramebufferRgba8(frame.display.framebuffer(), frame.width, frame.height);
      if (const char* keep = std::getenv("CB_KEEP_FRAMES")) {
        const char* names[] = {"wait", "pressure", "targets", "result", "done"};
        writePng(std::string(keep) + "/calibrate_" + names[int(stage)] + "_" +
                     std::to_string(round++) + ".png",
                 rgba);
      }
      seen->first_frame.emplace(int(stage), std::move(rgba));
    };
    FrameLoop loop(*display_, pen);
    FrameLoopResult result;
    EXPECT_TRUE(loop.run(flow, options, &result, &error)) << error;
    return result;
  }
  static const uint8_t* px(const ImageRgba8& image, double x, double y) {
    return image.at(int(x), int(y));
  }

  fs::path root_;
  std::unique_ptr<Display> display_;
  glm::dmat3 area_{1.0};
};

TEST_F(CalibrateScreensTest, TapsRedoAndAcceptWithThePenSaveTheProfile) {
  // Round 1 on a skewed tablet, a tap on Redo; round 2 on a shifted tablet, a tap on Accept.
  Script script;
  const std::string path = open(&script, "taps.cbj");
  const std::vector<glm::dvec2> targets = targetLayout(9, kW, kH);
  for (const glm::dvec2& t : targets) script.tap(mmFor(t, distortion()));
  const CalibrateBox redo = CalibrateResultScreen::redoBox(kW, kH);
  const CalibrateBox accept = CalibrateResultScreen::acceptBox(kW, kH);
  script.tap(mmFor({redo.x + redo.w / 2, redo.y + redo.h / 2}, glm::dmat3(1.0)));
  for (const glm::dvec2& t : targets) script.tap(mmFor(t, shift()));
  script.tap(mmFor({accept.x + accept.w / 2, accept.y + accept.h / 2}, glm::dmat3(1.0)));
  script.w.close();

  ReplayOptions replay;
  replay.realtime = false;
  replay.batch = 16;
  ReplayPenSource pen(path, replay);
  JournalWriter record;
  ASSERT_TRUE(record.open((root_ / "record.cbj").string()));
  CalibrateFlowOptions options;
  options.config_dir = (root_ / "config").string();
  options.state_dir = (root_ / "state").string();
  options.journal = &record;
  std::vector<std::string> log;
  options.log = [&](const std::string& line) { log.push_back(line); };
  int outcomes = 0;
  options.on_done = [&](const CalibrateOutcome&) { ++outcomes; };
  CalibrateFlowScreen flow(&pen, kW, kH, options);
  Seen seen;
  const FrameLoopResult result = run(flow, &pen, &seen);
  record.close();

  EXPECT_EQ(result.quit_reason, "calibration saved");
  EXPECT_EQ(outcomes, 1);
  ASSERT_TRUE(flow.outcome());
  ASSERT_EQ(flow.outcome()->kind, CalibrateOutcome::Kind::kSaved) << flow.outcome()->message;
  using Stage = CalibrateFlowScreen::Stage;
  // The replay is connected at once: the first frame already shows the targets.
  const std::vector<Stage> expected = {Stage::kTargets, Stage::kResult, Stage::kTargets,
                                       Stage::kResult};
  EXPECT_EQ(seen.stages, expected);
  bool said_redo = false;
  for (const std::string& line : log) said_redo |= line == "redo";
  EXPECT_TRUE(said_redo);

  // What the screens showed: the first target's red centre dot and white cross; on the result
  // screen the green Accept and orange Redo boxes and a red square where each tap lands.
  const ImageRgba8& first = seen.first_frame.at(int(Stage::kTargets));
  // The centre dot: red while the pen is up, dark green while it is down (the first frame
  // already has the first tap's touch-down).
  const uint8_t* dot = px(first, targets[0].x, targets[0].y);
  EXPECT_TRUE((dot[0] == 255 && std::abs(dot[1] - 77) <= 1) ||
              (dot[0] == 51 && std::abs(dot[1] - 77) <= 1))
      << int(dot[0]) << "," << int(dot[1]) << "," << int(dot[2]);
  EXPECT_EQ(px(first, targets[0].x + 20, targets[0].y)[2], 255);
  EXPECT_LT(px(first, targets[4].x + 20, targets[4].y)[0], 40) << "one target at a time";
  const ImageRgba8& shown = seen.first_frame.at(int(Stage::kResult));
  const uint8_t* a = px(shown, accept.x + 5, accept.y + 5);
  EXPECT_EQ(a[0], 51);
  EXPECT_EQ(a[1], 166);
  EXPECT_EQ(a[2], 64);
  const uint8_t* r = px(shown, redo.x + 5, redo.y + 5);
  EXPECT_EQ(r[0], 230);
  EXPECT_EQ(r[1], 128);
  EXPECT_EQ(px(shown, targets[8].x, targets[8].y)[0], 255) << "tap 8 lands on its target";

  // The saved profile corrects the second round's error over the whole screen.
  ProfileParseResult saved = readCalibrationProfile(flow.outcome()->saved_path);
  ASSERT_TRUE(saved.profile) << flow.outcome()->saved_path;
  EXPECT_EQ(flow.outcome()->saved_path, (root_ / "state/profiles/056a-00b9.toml").string());
  EXPECT_EQ(saved.profile->fit_kind, PointFitKind::kHomography);
  EXPECT_EQ(saved.profile->fit_points, 9);
  EXPECT_LT(saved.profile->fit_max_px, 0.5);
  for (const glm::dvec2& p : targetLayout(9, kW, kH, 0.0))
    EXPECT_LT(
        glm::length(applyTransform(saved.profile->correction, p) - applyTransform(shift(), p)), 0.5)
        << p.x << "," << p.y;
  // The record holds the markers, one redo and the accepted profile last.
  JournalReadResult rec = readJournal((root_ / "record.cbj").string());
  ASSERT_TRUE(rec.error.empty()) << rec.error;
  int target_markers = 0, redos = 0;
  for (const JournalRecord& rr : rec.records) {
    if (rr.type != JournalRecordType::kMarker) continue;
    target_markers += rr.text().rfind("calibrate target ", 0) == 0;
    redos += rr.text() == kCalibrateRedoMarker;
  }
  EXPECT_EQ(target_markers, 9);
  EXPECT_EQ(redos, 1);
  ASSERT_FALSE(rec.records.empty());
  EXPECT_EQ(rec.records.back().type, JournalRecordType::kCalibration);
}

TEST_F(CalibrateScreensTest, LightThenFirmPressSetsTheRange) {
  Script script;
  const std::string path = open(&script, "presses.cbj");
  auto press = [&](float level, int n) {
    for (int i = 0; i < n; ++i)
      script.emit({100, 70}, level > 0 ? level + 0.004f * ((i % 5) - 2) : 0.0f,
                  level > 0 ? 0.0f : 0.7f);
  };
  press(0.0f, 20);
  press(0.15f, 120);  // light
  press(0.0f, 20);
  press(0.55f, 120);  // firm
  press(0.0f, 20);
  script.w.close();
  ReplayOptions replay;
  replay.realtime = false;
  replay.batch = 32;
  ReplayPenSource pen(path, replay);
  CalibrateFlowOptions options;
  options.task = CalibrateFlowOptions::Task::kPressure;
  options.config_dir = (root_ / "config").string();
  options.state_dir = (root_ / "state").string();
  CalibrateFlowScreen flow(&pen, kW, kH, options);
  Seen seen;
  const FrameLoopResult result = run(flow, &pen, &seen);
  EXPECT_EQ(result.quit_reason, "calibration pressure range set");
  ASSERT_TRUE(flow.outcome());
  ASSERT_EQ(flow.outcome()->kind, CalibrateOutcome::Kind::kPressureRange)
      << flow.outcome()->message;
  ASSERT_TRUE(flow.outcome()->pressure.range);
  const PressureRange range = *flow.outcome()->pressure.range;
  EXPECT_NEAR(range.hi, 0.555f, 0.01f);
  EXPECT_NEAR(range.apply(0.15f), 0.2f, 0.02f);  // the light press gives the light target
  ASSERT_TRUE(seen.first_frame.count(int(CalibrateFlowScreen::Stage::kPressure)));
  // The light step's pale box.
  const uint8_t* box =
      px(seen.first_frame.at(int(CalibrateFlowScreen::Stage::kPressure)), kW * 0.5, kH * 0.5);
  EXPECT_EQ(box[2], 242);
}

TEST_F(CalibrateScreensTest, WaitsForThePenAndEscCancelsAPushedFlow) {
  // No tablet: an evdev source over an empty input folder keeps searching.
  fs::create_directories(root_ / "input");
  EvdevPenSourceOptions evdev;
  evdev.input_dir = (root_ / "input").string();
  EvdevPenSource pen(evdev);
  CalibrateFlowOptions options;
  options.config_dir = (root_ / "config").string();
  options.state_dir = (root_ / "state").string();
  options.esc_quits = false;  // as an operator panel pushes it: Esc cancels the flow
  std::optional<CalibrateOutcome> told;
  options.on_done = [&](const CalibrateOutcome& o) { told = o; };
  CalibrateFlowScreen flow(&pen, kW, kH, options);
  Seen seen;
  FrameLoopResult result = run(flow, &pen, &seen, "", 5);
  EXPECT_EQ(result.quit_reason, "frame limit");
  EXPECT_EQ(flow.stage(), CalibrateFlowScreen::Stage::kWaitForPen);
  EXPECT_FALSE(told);
  ASSERT_EQ(seen.stages.size(), 1u);
  // Dark red: waiting for the pen (the words say what to do; look at the kept frame).
  const uint8_t* corner = px(seen.first_frame.at(0), 5, kH - 5);
  EXPECT_EQ(corner[0], 64);
  EXPECT_EQ(corner[1], 13);
  const std::vector<std::string> words = flow.words();
  EXPECT_NE(std::find(words.begin(), words.end(), "Esc goes back without saving."), words.end())
      << "a pushed flow says Esc goes back, not that it quits";
  // Esc is the flow's to handle: it reports a cancel through the callback, nothing is saved.
  result = run(flow, &pen, &seen, "esc");
  EXPECT_EQ(result.quit_reason, "calibration cancelled");
  ASSERT_TRUE(told);
  EXPECT_EQ(told->kind, CalibrateOutcome::Kind::kCancelled);
  EXPECT_FALSE(fs::exists(root_ / "state/profiles"));
}

}  // namespace
}  // namespace cb
