// The kiosk's screens through the shell's frame loop on EGL surfaceless (llvmpipe), with the
// bundled config and attract journal, a scripted pen and a ManualClock that the loop's every
// iteration moves on (no sleeping): the attract loop replaying and orbiting and handing over on
// the first proximity, the idle countdown and reset, visitor texts in English and Chinese, the
// operator panel behind its key combination and PIN (every action logged), the gallery with its
// quota and journal retention, and "reconnect the pen" when the tablet goes away mid-visit.
// CB_KEEP_FRAMES=DIR writes the frames checked, for looking.
#include <gtest/gtest.h>
#include <xkbcommon/xkbcommon-keysyms.h>

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>

#include "app/core/config_paths.h"
#include "app/kiosk/operator_pin.h"
#include "app/kiosk/unsaved_visit.h"
#include "app/render/image_io.h"
#include "app/session/session_replay.h"
#include "app/shell/calibrate/calibrate_result_screen.h"
#include "app/shell/frame_loop.h"
#include "app/shell/keymap.h"
#include "app/shell/kiosk/kiosk_error_screen.h"
#include "app/shell/kiosk/kiosk_screen.h"
#include "app/study/volume_export.h"
#include "app/volume/volume_file.h"
#include "calibration/n_point_calibration.h"
#include "calibration/pressure_range.h"
#include "calibration/profile_store.h"
#include "scripted_pen_source.h"
#include "small_tmpfs.h"
#include "tests/support/test_display.h"

namespace cb {
namespace {
namespace fs = std::filesystem;

constexpr int kW = 640, kH = 360, kGrid = 64;
const std::string kConfigDir = std::string(CB_SOURCE_DIR) + "/config";

double density(const Volume& v) {
  double sum = 0.0;
  for (float d : v.toDense()) sum += d;
  return sum;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Whether a calibration screen in the kiosk says that Esc goes back to the operator panel (as
// it does there) and never that Esc quits (it does not: a kiosk has no way out).
void expectEscGoesBackToThePanel(const std::vector<std::string>& words) {
  std::string all;
  for (const std::string& w : words) all += w + "\n";
  EXPECT_NE(all.find("Esc goes back to the operator panel without saving."), std::string::npos)
      << all;
  EXPECT_EQ(all.find("quit"), std::string::npos) << all;
}

void keep(const std::string& name, const ImageRgba8& image) {
  if (const char* dir = std::getenv("CB_KEEP_FRAMES"))
    writePng(std::string(dir) + "/" + name, image);
}

// A kiosk with the bundled settings (changed by `adjust`), the bundled attract journal, a
// scripted pen and a data dir of its own.
class KioskRig {
 public:
  // The operator PIN is set to "2468" unless `set_pin` is false (the first start). A `name`
  // that is an absolute path is the data dir as it is (a restart: nothing removed or set).
  explicit KioskRig(const std::string& name, std::function<void(KioskConfig&)> adjust = {},
                    std::function<void(const std::string& data_dir)> before = {},
                    bool set_pin = true, glm::ivec2 size = {kW, kH})
      : w_(size.x),
        h_(size.y),
        data_dir_(
            name.front() == '/'
                ? name
                : (fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()))).string()),
        pen_(w_, h_) {
    const bool restart = name.front() == '/' && fs::exists(data_dir_);
    if (!restart) fs::remove_all(data_dir_);
    fs::create_directories(data_dir_);
    if (before) before(data_dir_);
    std::string error;
    if (set_pin && !restart && !OperatorPinGuard(data_dir_).setPin("2468", &error))
      throw std::runtime_error(error);
    display_ = test::openTestDisplay(w_, h_, &error);
    if (!display_) throw std::runtime_error(error);
    if (!renderer_.init(&error)) throw std::runtime_error(error);
    KioskSetup setup;
    setup.config = loadKioskConfig(kConfigDir + "/kiosk.toml");
    if (adjust) adjust(setup.config);
    setup.texts = KioskTexts::load(kConfigDir + "/kiosk/texts.toml", setup.config.language,
                                   [this](const std::string& line) { log_.push_back(line); });
    const JournalReadResult attract = readJournal(kConfigDir + "/" + setup.config.attract_journal);
    if (!attract.error.empty()) throw std::runtime_error(attract.error);
    setup.attract_journal = attract.records;
    setup.data_dir = data_dir_;
    setup.config_dir = kConfigDir;
    setup.visitor_settings = {w_, h_, kGrid};
    setup.on_status = [this](const std::string& status) { statuses_.push_back(status); };
    setup.on_problem = [this](const std::string& problem) { problems_.push_back(problem); };
    setup.on_storage = [this](const std::string& state) { storage_.push_back(state); };
    PaintLoopOptions options;
    options.visitor_mode = true;
    options.orbit_degrees_per_second = 0.0f;
    options.config_dir = kConfigDir;
    options.state_dir = data_dir_;
    options.clock = &clock_;
    options.before_start_again = [this] { kiosk_->keepFinishedCloud("start again"); };
    paint_ = std::make_unique<PaintScreen>(*display_, renderer_, demo_, Light{}, options);
    paint_->attachPen(&pen_, nullptr);
    kiosk_ = std::make_unique<KioskScreen>(*display_, renderer_, *paint_, &pen_, clock_,
                                           std::move(setup));
  }
  ~KioskRig() {
    kiosk_.reset();
    std::error_code ec;  // a mount point (the disk-full test) stays; its owner unmounts it
    if (!keep_data_dir_) fs::remove_all(data_dir_, ec);
  }
  void keepDataDir() { keep_data_dir_ = true; }

  // Runs `frames` loop iterations, the clock moving `step_s` after each; returns the quit reason.
  std::string run(long frames, double step_s = 0.1) {
    FrameLoopOptions options;
    options.max_frames = frames;
    options.clock = &clock_;
    options.initial_keys.swap(keys_);
    options.each_iteration = [&](bool) { clock_.advance(int64_t(step_s * 1e9)); };
    options.after_draw = [&](const FrameContext&) {
      last_frame_ = readFramebufferRgba8(display_->framebuffer(), w_, h_);
    };
    FrameLoop loop(*display_, &pen_);
    FrameLoopResult result;
    std::string error;
    if (!loop.run(*kiosk_, options, &result, &error)) throw std::runtime_error(error);
    return result.quit_reason;
  }
  // Runs until `done` (checked after every iteration) or `limit` iterations; true when done.
  bool runUntil(const std::function<bool()>& done, long limit, double step_s) {
    for (long i = 0; i < limit; ++i) {
      run(1, step_s);
      if (done()) return true;
    }
    return false;
  }
  bool key(uint32_t keysym, uint32_t modifiers = 0) {
    return kiosk_->onKey(DisplayEvent::key(keysym, modifiers), clock_.nowNs());
  }
  // '\r' is Enter.
  void type(const std::string& keys) {
    for (char c : keys) key(c == '\r' ? 0xff0du : uint32_t(c));
  }
  // Keys (keymap.h names) the frame loop delivers at the start of the next run, as from the
  // display: the ones the kiosk does not take become commands.
  void press(const std::string& keys) {
    std::string error;
    if (!parseKeyList(keys, &keys_, &error)) throw std::runtime_error(error);
  }

  KioskScreen& kiosk() { return *kiosk_; }
  PaintScreen& paint() { return *paint_; }
  test::ScriptedPenSource& pen() { return pen_; }
  ManualClock& clock() { return clock_; }
  const std::string& dataDir() const { return data_dir_; }
  const ImageRgba8& lastFrame() const { return last_frame_; }
  const std::vector<std::string>& textLog() const { return log_; }
  const std::vector<std::string>& statuses() const { return statuses_; }
  const std::vector<std::string>& problems() const { return problems_; }
  const std::vector<std::string>& storageStates() const { return storage_; }

 private:
  int w_, h_;
  std::string data_dir_;
  bool keep_data_dir_ = false;
  std::unique_ptr<Display> display_;
  VolumeRenderer renderer_;
  ManualClock clock_{1'000'000'000};
  test::ScriptedPenSource pen_;
  Volume demo_{glm::ivec3(8)};
  std::unique_ptr<PaintScreen> paint_;
  std::unique_ptr<KioskScreen> kiosk_;
  ImageRgba8 last_frame_;
  std::vector<std::string> log_, statuses_, problems_, storage_;
  std::vector<DisplayEvent> keys_;
};

using State = KioskScreen::State;

// Files under `dir` (recursively) whose name contains `part`.
std::vector<std::string> filesNamed(const std::string& dir, const std::string& part) {
  std::vector<std::string> found;
  std::error_code ec;
  for (const auto& item : fs::recursive_directory_iterator(dir, ec))
    if (item.path().filename().string().find(part) != std::string::npos)
      found.push_back(item.path().string());
  return found;
}

// A visitor paints, then idles until the attract loop is back.
void paintAVisit(KioskRig& rig) {
  rig.pen().hover(rig.clock().nowNs());
  rig.run(1);
  rig.pen().stroke(rig.clock().nowNs());
  rig.run(3);
  ASSERT_TRUE(rig.runUntil([&] { return rig.kiosk().state() == State::kAttract; }, 80, 0.25));
}

TEST(KioskScreens, AttractReplaysOrbitsHandsOverAndResumesAfterIdle) {
  KioskRig rig("cb_kiosk_attract", [](KioskConfig& c) {
    c.attract_hold_seconds = 2.0;
    c.idle_seconds = 6.0;
    c.warning_seconds = 3.0;
  });
  KioskScreen& kiosk = rig.kiosk();
  rig.run(1);
  ASSERT_EQ(kiosk.state(), State::kAttract);
  EXPECT_GT(kiosk.attract().recordCount(), 500u);
  kiosk.attract().waitUntilPrepared();  // the strokes are mapped on the replay's worker thread
  const glm::vec3 eye0 = kiosk.attract().shownCamera().eye;
  // The journal replays at its own pace on the clock: half a second per frame here.
  ASSERT_TRUE(rig.runUntil(
      [&] { return kiosk.attract().recordsPlayed() == kiosk.attract().recordCount(); }, 200, 0.5))
      << kiosk.attract().recordsPlayed() << " of " << kiosk.attract().recordCount();
  EXPECT_TRUE(kiosk.attract().problems().empty()) << kiosk.attract().problems().front();
  EXPECT_GT(density(kiosk.attract().volume()), 0.0) << "the replayed strokes became a cloud";
  EXPECT_GT(glm::length(kiosk.attract().shownCamera().eye - eye0), 0.1f) << "the camera orbits";
  rig.run(1, 0.0);
  keep("kiosk_attract_replayed.png", rig.lastFrame());
  // Held for hold_seconds, then the replay starts again on an empty sky.
  ASSERT_TRUE(rig.runUntil([&] { return kiosk.attract().loopsCompleted() == 1; }, 20, 0.5));
  EXPECT_EQ(density(kiosk.attract().volume()), 0.0);

  // The first pen proximity hands over at once, on an empty canvas.
  rig.pen().hover(rig.clock().nowNs());
  rig.run(1);
  EXPECT_EQ(kiosk.state(), State::kVisitor);
  ASSERT_NE(kiosk.visitorSession(), nullptr);
  EXPECT_EQ(density(kiosk.visitorSession()->volume()), 0.0);
  EXPECT_FALSE(kiosk.visitorSession()->history().canUndo());
  rig.pen().stroke(rig.clock().nowNs());
  rig.run(3);
  EXPECT_GT(density(kiosk.visitorSession()->volume()), 0.0) << "the visitor painted";
  // Left alone: the countdown, then the attract loop again.
  ASSERT_TRUE(rig.runUntil([&] { return !kiosk.notice().empty(); }, 60, 0.25));
  EXPECT_EQ(kiosk.notice().rfind("Still there? The sky clears in 3 s", 0), 0u) << kiosk.notice();
  keep("kiosk_countdown_en.png", rig.lastFrame());
  ASSERT_TRUE(rig.runUntil([&] { return kiosk.state() == State::kAttract; }, 60, 0.25));
  EXPECT_EQ(kiosk.idleResets(), 1);
  EXPECT_LT(kiosk.attract().recordsPlayed(), kiosk.attract().recordCount()) << "replay restarted";
  // The next visitor starts on an empty canvas and cannot undo into the previous cloud.
  rig.pen().hover(rig.clock().nowNs());
  rig.run(1);
  EXPECT_EQ(kiosk.state(), State::kVisitor);
  EXPECT_EQ(density(kiosk.visitorSession()->volume()), 0.0);
  EXPECT_FALSE(kiosk.visitorSession()->history().canUndo());
  // ... in the default sky, however far the previous visitor grew theirs (a fresh session).
  EXPECT_EQ(kiosk.visitorSession()->sky().span, kDefaultSkySpan);
  EXPECT_EQ(kiosk.visitorSession()->volume().dims(), kiosk.visitorSession()->sky().dims());
  EXPECT_EQ(kiosk.visits(), 2);
  // Each visitor's journal is in the data dir and replays to the cloud they painted.
  size_t journals = 0;
  for (const auto& entry : fs::directory_iterator(rig.dataDir() + "/sessions"))
    journals += entry.path().extension() == ".cbj";
  EXPECT_EQ(journals, 2u);
  EXPECT_TRUE(rig.statuses().size() >= 4u);
}

TEST(KioskScreens, VisitorTextsInEnglishAndChinese) {
  std::map<std::string, ImageRgba8> frames;
  for (const char* language : {"en", "zh"}) {
    KioskRig rig(std::string("cb_kiosk_lang_") + language, [&](KioskConfig& c) {
      c.language = language;
      c.gallery_enabled = true;
    });
    rig.run(2, 0.0);
    frames[language] = rig.lastFrame();
    keep(std::string("kiosk_attract_") + language + ".png", rig.lastFrame());
    EXPECT_TRUE(rig.textLog().empty()) << "every key is bundled in " << language;
    // The reconnect screen in the same language, for looking.
    rig.pen().hover(rig.clock().nowNs());
    rig.run(1);
    rig.pen().unplug();
    rig.run(2, 0.0);
    EXPECT_EQ(rig.kiosk().state(), KioskScreen::State::kReconnect);
    keep(std::string("kiosk_reconnect_") + language + ".png", rig.lastFrame());
  }
  // The invitation band (38%..60% of the height) differs between the languages; the sky above
  // it does not (the same replay, the same clock).
  const auto differing = [&](int y0, int y1) {
    long count = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < kW; ++x)
        for (int c = 0; c < 3; ++c)
          count += std::abs(int(frames["en"].at(x, y)[c]) - int(frames["zh"].at(x, y)[c])) > 40;
    return count;
  };
  EXPECT_GT(differing(int(0.38 * kH), int(0.6 * kH)), 500);
  EXPECT_EQ(differing(0, int(0.3 * kH)), 0);
}

TEST(KioskScreens, OperatorPanelOnlyAfterCombinationAndPinEveryActionLogged) {
  KioskRig rig("cb_kiosk_operator");
  KioskScreen& kiosk = rig.kiosk();
  rig.pen().hover(rig.clock().nowNs());
  rig.run(1);
  rig.pen().stroke(rig.clock().nowNs());
  rig.run(3);
  ASSERT_EQ(kiosk.state(), State::kVisitor);
  // Visitor mode: only painting, erasing, camera, undo and start again.
  EXPECT_FALSE(kiosk.allowsQuit());
  kiosk.onCommand(Command::kSave, rig.clock().nowNs());
  kiosk.onCommand(Command::kModeLight, rig.clock().nowNs());
  EXPECT_EQ(kiosk.visitorSession()->mode(), Mode::kPaint);
  // The PIN alone is just keys for the painter.
  EXPECT_FALSE(rig.key('2'));
  EXPECT_EQ(kiosk.state(), State::kVisitor);
  // The combination asks for the PIN; three wrong ones lock the panel for a minute.
  EXPECT_TRUE(rig.key('o', DisplayEvent::kCtrl | DisplayEvent::kAlt));
  EXPECT_EQ(kiosk.state(), State::kOperator);
  rig.run(1, 0.0);
  keep("kiosk_operator_pin.png", rig.lastFrame());
  rig.type(
      "1111\r"
      "1357\r"
      "0000\r");
  EXPECT_FALSE(kiosk.operatorPanel().unlocked());
  rig.type("2468\r");
  EXPECT_FALSE(kiosk.operatorPanel().unlocked()) << "locked after three wrong PINs";
  rig.clock().advance(61'000'000'000);
  rig.type("2468\r");
  ASSERT_TRUE(kiosk.operatorPanel().unlocked());
  rig.type("2");  // idle +15 s
  rig.type("3");  // countdown -5 s
  rig.type("g");  // gallery on
  rig.type("e");  // export the visitor's cloud (C, the calibration, is tested below)
  rig.run(1, 0.0);
  keep("kiosk_operator_panel.png", rig.lastFrame());
  EXPECT_EQ(kiosk.config().idle_seconds, 105.0);
  EXPECT_EQ(kiosk.config().warning_seconds, 5.0);
  EXPECT_TRUE(kiosk.config().gallery_enabled);
  std::vector<fs::path> exports;
  for (const auto& entry : fs::directory_iterator(rig.dataDir() + "/exports"))
    exports.push_back(entry.path());
  ASSERT_EQ(exports.size(), 1u);
  const Volume exported = loadVolume((exports[0] / "cloud.cbvol").string());
  EXPECT_EQ(volumeChecksum(exported), volumeChecksum(kiosk.visitorSession()->volume()));
  EXPECT_EQ(readPng((exports[0] / "render.png").string()).width, kW);
  rig.type("x");
  rig.type("n");  // not confirmed
  EXPECT_EQ(rig.run(1, 0.0), "frame limit");
  rig.type("xy");
  EXPECT_EQ(rig.run(1, 0.0), "operator shutdown");
  // Saving is the operator's: the visitor's Ctrl+S wrote nothing.
  for (const auto& entry : fs::recursive_directory_iterator(rig.dataDir()))
    EXPECT_NE(entry.path().extension(), ".vol") << entry.path();
  const std::string log = slurp(rig.dataDir() + "/operator.log");
  for (const char* action :
       {"pin-asked", "wrong-pin (1 in a row)", "wrong-pin (3 in a row)", "locked-out for 60 s",
        "panel-opened", "set-idle-seconds 105", "set-warning-seconds 5", "toggle-gallery on",
        "export-cloud ", "shutdown", "panel-closed"})
    EXPECT_NE(log.find(std::string("Z ") + action), std::string::npos) << action << "\n" << log;
  EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 12) << log;
}

// systemctl stop mid-visit (SIGTERM ends the loop; `cloudbrush kiosk` then calls stopping()):
// the visitor's cloud is kept in the gallery, their journal closed whole.
TEST(KioskScreens, StoppedMidVisitTheVisitorsCloudIsKept) {
  KioskRig rig("cb_kiosk_stop", [](KioskConfig& c) { c.gallery_enabled = true; });
  KioskScreen& kiosk = rig.kiosk();
  rig.pen().hover(rig.clock().nowNs());
  rig.run(1);
  rig.pen().stroke(rig.clock().nowNs());
  rig.run(3);
  ASSERT_EQ(kiosk.state(), State::kVisitor);
  const uint64_t painted = volumeChecksum(kiosk.visitorSession()->volume());
  kiosk.stopping();
  ASSERT_EQ(kiosk.gallerySaved(), (std::vector<long>{1}));
  EXPECT_EQ(volumeChecksum(loadVolume(rig.dataDir() + "/gallery/000001/cloud.cbvol")), painted);
  const std::vector<std::string> journals = filesNamed(rig.dataDir() + "/sessions", "-visit1");
  ASSERT_EQ(journals.size(), 1u);
  const SessionReplay replay =
      replaySession(readJournal(journals[0]), BrushConfig{}, MappingConfig{});
  ASSERT_TRUE(replay.session) << replay.journal_error;
  EXPECT_EQ(volumeChecksum(replay.session->volume()), painted) << "the journal replays to it";
}

// The child of KilledMidVisitTheNextStartKeepsTheCloudOnce (run by it, not on its own): a
// visitor paints two strokes with the gallery on, the checksum of their cloud goes to
// $CB_KILLED_DATA_DIR/painted, then the process kills itself with SIGKILL mid-visit.
TEST(KioskScreens, DISABLED_PaintThenBeKilled) {
  const char* dir = std::getenv("CB_KILLED_DATA_DIR");
  ASSERT_NE(dir, nullptr);
  KioskRig rig(dir, [](KioskConfig& c) { c.gallery_enabled = true; });
  rig.pen().hover(rig.clock().nowNs());
  rig.run(1);
  for (int i = 0; i < 2; ++i) {
    rig.pen().stroke(rig.clock().nowNs());
    rig.run(3);
  }
  ASSERT_EQ(rig.kiosk().state(), State::kVisitor);
  ASSERT_GT(density(rig.kiosk().visitorSession()->volume()), 0.0);
  std::ofstream(std::string(dir) + "/painted")
      << volumeChecksum(rig.kiosk().visitorSession()->volume()) << "\n";
  ::kill(::getpid(), SIGKILL);
}

// kill -9 in the middle of a visit (the test's child process, above): the visitor's journal is
// left as the kill left it. The next start replays it into the gallery as one entry (the cloud
// the visitor painted) and logs it; the start after that adds nothing. A kill between that save
// and the end of the recovery (the record still names the journal, with the entry number before
// the save) does not save it twice either.
TEST(KioskScreens, KilledMidVisitTheNextStartKeepsTheCloudOnce) {
  const std::string dir =
      (fs::temp_directory_path() / ("cb_kiosk_killed_" + std::to_string(::getpid()))).string();
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string error;
  ASSERT_TRUE(OperatorPinGuard(dir).setPin("2468", &error)) << error;
  // Everything the child needs is made before the fork (it only calls exec).
  const std::string self = fs::read_symlink("/proc/self/exe").string();
  ::setenv("CB_KILLED_DATA_DIR", dir.c_str(), 1);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::execl(self.c_str(), self.c_str(), "--gtest_filter=KioskScreens.DISABLED_PaintThenBeKilled",
            "--gtest_also_run_disabled_tests", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "status " << status;
  const std::string painted = slurp(dir + "/painted");
  ASSERT_FALSE(painted.empty()) << "the child painted";
  const uint64_t checksum = std::stoull(painted);
  ASSERT_EQ(filesNamed(dir + "/sessions", "-visit1").size(), 1u);
  ASSERT_TRUE(fs::exists(dir + "/unsaved-visit")) << "the kill left the visit's record";
  EXPECT_FALSE(fs::exists(dir + "/gallery/000001")) << "nothing was saved before the kill";
  const auto entries = [&] { return filesNamed(dir + "/gallery", "cloud.cbvol").size(); };
  {
    testing::internal::CaptureStderr();
    KioskRig restarted(dir, [](KioskConfig& c) { c.gallery_enabled = true; });
    restarted.keepDataDir();
    const std::string log = testing::internal::GetCapturedStderr();
    std::fputs(log.c_str(), stderr);
    EXPECT_EQ(restarted.kiosk().gallerySaved(), (std::vector<long>{1}));
    EXPECT_EQ(entries(), 1u);
    EXPECT_EQ(volumeChecksum(loadVolume(dir + "/gallery/000001/cloud.cbvol")), checksum)
        << "the entry is the cloud the killed visitor painted";
    EXPECT_NE(log.find("killed visit (journal " + dir + "/sessions/"), std::string::npos) << log;
    EXPECT_NE(log.find("replayed (2 strokes) and saved to the gallery as 000001"),
              std::string::npos)
        << log;
    EXPECT_FALSE(fs::exists(dir + "/unsaved-visit"));
    EXPECT_EQ(restarted.kiosk().state(), State::kAttract);
  }
  {
    KioskRig again(dir, [](KioskConfig& c) { c.gallery_enabled = true; });
    again.keepDataDir();
    EXPECT_TRUE(again.kiosk().gallerySaved().empty()) << "the next start adds nothing";
    EXPECT_EQ(entries(), 1u);
  }
  // Killed after the save, before the record went: the record says which entry was the newest
  // before the save (0), entry 1 is newer, so the cloud is in already.
  const std::string journal = fs::path(filesNamed(dir + "/sessions", "-visit1")[0]).filename();
  ASSERT_TRUE(writeUnsavedVisit(dir, {journal, 0}, &error)) << error;
  {
    testing::internal::CaptureStderr();
    KioskRig again(dir, [](KioskConfig& c) { c.gallery_enabled = true; });
    const std::string log = testing::internal::GetCapturedStderr();
    std::fputs(log.c_str(), stderr);
    EXPECT_TRUE(again.kiosk().gallerySaved().empty());
    EXPECT_EQ(entries(), 1u) << "not saved twice";
    EXPECT_NE(log.find("its cloud was saved as 1 before the last stop"), std::string::npos) << log;
    EXPECT_FALSE(fs::exists(dir + "/unsaved-visit"));
  }  // removes the data dir
}

DisplayEvent pointerEvent(DisplayEvent::Kind kind, float x, float y) {
  DisplayEvent e;
  e.kind = kind;
  e.x = x;
  e.y = y;
  e.button = kind == DisplayEvent::Kind::PointerMove ? 0 : 1;
  return e;
}

// A visitor at a 1920×1080 kiosk with only a mouse (no tablet), product defaults but for
// `language`: everything the screens write on the way (attract, painting, an answer, the menu,
// the help, start again and its gallery notice, the countdown) is one of the kiosk's visitor
// texts in that language (config/kiosk/texts.toml), line by line, with numbers for its
// {placeholders}: no keys, brush or pressure figures, paths or driver status. Every text drawn
// is seen through UiOverlay's text observer, and the painter's font has each of its characters.
// The frames go to CB_KEEP_FRAMES.
void expectOnlyVisitorTexts(const std::string& language) {
  constexpr int kW1080 = 1920, kH1080 = 1080;
  std::vector<std::pair<std::string, std::string>> drawn;  // (screen, text)
  std::string screen = "attract";
  UiOverlay::setTextObserver([&](const std::string& text) { drawn.emplace_back(screen, text); });
  {
    KioskRig rig("cb_kiosk_visitor_texts_" + language,
                 [&](KioskConfig& c) {
                   c.language = language;
                   c.gallery_enabled = true;
                   c.idle_seconds = 8.0;
                   c.warning_seconds = 3.0;
                 },
                 {}, true, {kW1080, kH1080});
    KioskScreen& kiosk = rig.kiosk();
    const auto shot = [&](const std::string& name) {
      keep("visitor_1080_" + language + "_" + name + ".png", rig.lastFrame());
    };
    rig.pen().unplug();  // a kiosk without a tablet: the mouse paints
    rig.run(2, 0.0);
    shot("attract");
    screen = "visitor";
    const auto mouse = [&](DisplayEvent::Kind kind, float fx, float fy) {
      kiosk.onPointer(pointerEvent(kind, fx * kW1080, fy * kH1080));
    };
    mouse(DisplayEvent::Kind::PointerMove, 0.5f, 0.5f);
    rig.run(1);
    ASSERT_EQ(kiosk.state(), State::kVisitor);
    mouse(DisplayEvent::Kind::PointerMove, 0.35f, 0.55f);
    mouse(DisplayEvent::Kind::PointerDown, 0.35f, 0.55f);
    for (int i = 1; i <= 10; ++i) {
      mouse(DisplayEvent::Kind::PointerMove, 0.35f + 0.03f * float(i), 0.55f - 0.01f * float(i));
      rig.run(1, 0.05);
    }
    mouse(DisplayEvent::Kind::PointerUp, 0.65f, 0.45f);
    rig.run(3);
    EXPECT_GT(density(kiosk.visitorSession()->volume()), 0.0) << "the mouse painted";
    shot("painted");
    screen = "answer";
    kiosk.onCommand(Command::kRedo, rig.clock().nowNs());
    rig.run(1, 0.0);
    shot("answer");
    screen = "menu";
    kiosk.onCommand(Command::kMenu, rig.clock().nowNs());
    rig.run(2, 0.0);
    shot("menu");
    screen = "help";
    kiosk.onCommand(Command::kHelp, rig.clock().nowNs());
    rig.run(2, 0.0);
    shot("help");
    kiosk.onCommand(Command::kHelp, rig.clock().nowNs());
    kiosk.onCommand(Command::kMenu, rig.clock().nowNs());
    screen = "start again";
    kiosk.onCommand(Command::kDeleteAll, rig.clock().nowNs());
    rig.run(2, 0.0);
    EXPECT_EQ(kiosk.gallerySaved(), (std::vector<long>{1}));
    shot("start_again");
    // The gallery's notice shows for a few seconds; then, left alone, the countdown.
    const std::string saved = kiosk.notice();
    EXPECT_FALSE(saved.empty());
    screen = "countdown";
    ASSERT_TRUE(
        rig.runUntil([&] { return !kiosk.notice().empty() && kiosk.notice() != saved; }, 80, 0.25));
    rig.run(1, 0.0);
    shot("countdown");
    ASSERT_NE(rig.paint().ui(), nullptr);
    for (const auto& [where, text] : drawn)
      EXPECT_EQ(rig.paint().ui()->missingGlyphs(text), 0) << where << ": " << text;
  }
  UiOverlay::setTextObserver({});
  const KioskTexts texts = KioskTexts::load(kConfigDir + "/kiosk/texts.toml", language, {});
  const auto escaped = [](const std::string& text) {
    static const std::regex special(R"([.^$|()\[\]{}*+?\\])");
    return std::regex_replace(text, special, R"(\$&)");
  };
  // Line by line: a label may join texts (the attract notice: gallery and recording notices).
  const auto lines = [](const std::string& text) {
    std::vector<std::string> out;
    size_t start = 0;
    for (size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1)
      out.push_back(text.substr(start, end - start));
    out.push_back(text.substr(start));
    return out;
  };
  std::vector<std::regex> allowed;
  for (const char* key : kKioskTextKeys)
    for (const std::string& line : lines(texts.text(key)))
      allowed.emplace_back(
          std::regex_replace(escaped(line), std::regex(R"(\\\{[a-z]+\\\})"), "[0-9]+"));
  std::map<std::string, int> per_screen;
  for (const auto& [where, text] : drawn) {
    ++per_screen[where];
    for (const std::string& line : lines(text)) {
      if (line.empty()) continue;
      const bool known = std::any_of(allowed.begin(), allowed.end(), [&](const std::regex& r) {
        return std::regex_match(line, r);
      });
      EXPECT_TRUE(known) << language << ", " << where << ": \"" << line
                         << "\" is not one of the kiosk's visitor texts";
    }
  }
  for (const char* where :
       {"attract", "visitor", "answer", "menu", "help", "start again", "countdown"})
    EXPECT_GT(per_screen[where], 0) << where << ": nothing drawn was seen";
}

TEST(KioskScreens, VisitorSeesOnlyTheKiosksTextsInEnglish) {
  expectOnlyVisitorTexts("en");
}

TEST(KioskScreens, VisitorSeesOnlyTheKiosksTextsInChinese) {
  expectOnlyVisitorTexts("zh");
}

// Every key the painter's visitor words read is one the kiosk's texts must hold in English (so
// a texts.toml without it is refused at start instead of showing nothing).
TEST(KioskScreens, EveryVisitorWordIsAKioskTextKey) {
  const std::vector<std::string> required(std::begin(kKioskTextKeys), std::end(kKioskTextKeys));
  for (const std::string& key : visitorWordKeys())
    EXPECT_NE(std::find(required.begin(), required.end(), key), required.end()) << key;
}

// The screen a bad config file or data dir shows instead of a restart loop: the problem as given
// (file and line) drawn as text on a plain background, and no key ends it.
TEST(KioskScreens, ErrorScreenShowsTheFileAndLineAndNoKeyEndsIt) {
  std::string error;
  std::unique_ptr<Display> display = test::openTestDisplay(kW, kH, &error);
  ASSERT_TRUE(display) << error;
  KioskErrorScreen screen("/etc/cloudbrush/kiosk.toml:8: visitor.idle_seconds must be a number");
  FrameLoopOptions options;
  options.max_frames = 3;
  ASSERT_TRUE(parseKeyList("esc,q,ctrl+c,alt+f4", &options.initial_keys, &error)) << error;
  ImageRgba8 frame;
  options.after_draw = [&](const FrameContext&) {
    frame = readFramebufferRgba8(display->framebuffer(), kW, kH);
  };
  FrameLoop loop(*display, nullptr);
  FrameLoopResult result;
  ASSERT_TRUE(loop.run(screen, options, &result, &error)) << error;
  EXPECT_EQ(result.quit_reason, "frame limit") << "Esc, q, Ctrl+C, Alt+F4 do not end it";
  ASSERT_EQ(frame.width, kW);
  // Text on the dark background: the title in red at the top (rows above 20 %), the problem in
  // white in its rows (22 %..36 % down).
  long red_title = 0, white_problem = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const uint8_t* p = frame.at(x, y);
      if (y < 0.2 * kH && p[0] > 200 && p[1] < 170) ++red_title;
      if (y > 0.22 * kH && y < 0.36 * kH && p[0] > 200 && p[1] > 200 && p[2] > 200) ++white_problem;
    }
  EXPECT_GT(red_title, 100) << "the title is drawn";
  EXPECT_GT(white_problem, 200) << "the problem's line is drawn";
  keep("kiosk_error_screen.png", frame);
}

// First start: no PIN and no default one. The combination asks for a new PIN, twice; it is
// stored hashed, logged without its digits, and asked for from then on.
TEST(KioskScreens, FirstStartAsksTheOperatorToSetThePin) {
  KioskRig rig("cb_kiosk_first_pin", {}, {}, /*set_pin=*/false);
  KioskScreen& kiosk = rig.kiosk();
  EXPECT_FALSE(kiosk.operatorPin().hasPin());
  ASSERT_TRUE(rig.key('o', DisplayEvent::kCtrl | DisplayEvent::kAlt));
  rig.type("2468");  // the old default does nothing
  EXPECT_FALSE(kiosk.operatorPanel().unlocked());
  rig.run(1, 0.0);
  keep("kiosk_first_pin.png", rig.lastFrame());
  rig.key(0xff0d);  // Enter: the new PIN once ...
  rig.type("9135");
  rig.key(0xff0d);  // ... differs from the first: asked again
  EXPECT_FALSE(kiosk.operatorPanel().unlocked());
  rig.type("975310");
  rig.key(0xff0d);
  rig.type("975310");
  rig.key(0xff0d);
  ASSERT_TRUE(kiosk.operatorPanel().unlocked());
  EXPECT_TRUE(kiosk.operatorPin().hasPin());
  rig.key(0xff1b);
  rig.run(1, 0.0);
  const std::string log = slurp(rig.dataDir() + "/operator.log");
  EXPECT_NE(log.find("Z pin-set\n"), std::string::npos) << log;
  EXPECT_EQ(log.find("975310"), std::string::npos) << "never the digits";
  EXPECT_EQ(slurp(rig.dataDir() + "/operator-pin").find("975310"), std::string::npos);
  // From now on the PIN is asked for.
  ASSERT_TRUE(rig.key('o', DisplayEvent::kCtrl | DisplayEvent::kAlt));
  rig.type("975310\r");
  EXPECT_TRUE(kiosk.operatorPanel().unlocked());
}

// PIN entry ends with Enter, not at a stored length: the right digits alone do not open the
// panel, nor does the prompt say how many digits there are; the right PIN and Enter open it,
// extra digits make it wrong.
TEST(KioskScreens, PinEntryEndsWithEnterAndShowsNoLength) {
  KioskRig rig("cb_kiosk_pin_enter");
  KioskScreen& kiosk = rig.kiosk();
  ASSERT_TRUE(rig.key('o', DisplayEvent::kCtrl | DisplayEvent::kAlt));
  rig.type("2468");
  rig.run(1, 0.0);
  EXPECT_FALSE(kiosk.operatorPanel().unlocked()) << "not before Enter";
  for (const UiLabel& label : kiosk.operatorPanel().labels()) {
    EXPECT_EQ(label.text.find("digits"), std::string::npos) << label.text;
    EXPECT_EQ(label.text.find("____"), std::string::npos) << label.text;
  }
  keep("kiosk_pin_prompt.png", rig.lastFrame());
  rig.type("0\r");  // 24680: one digit too many
  EXPECT_FALSE(kiosk.operatorPanel().unlocked());
  EXPECT_EQ(kiosk.operatorPin().failures(), 1);
  rig.type("\r");  // Enter alone is no try
  EXPECT_EQ(kiosk.operatorPin().failures(), 1);
  rig.type("2468\r");
  EXPECT_TRUE(kiosk.operatorPanel().unlocked());
}

// An operator combination with a function key (the KMS keyboard's built-in US table has them).
TEST(KioskScreens, OperatorCombinationWithAFunctionKey) {
  KioskRig rig("cb_kiosk_operator_f12", [](KioskConfig& c) { c.operator_keys = "ctrl+alt+f12"; });
  KioskScreen& kiosk = rig.kiosk();
  rig.run(1);
  EXPECT_TRUE(rig.key(XKB_KEY_o, DisplayEvent::kCtrl | DisplayEvent::kAlt));  // wakes, no panel
  EXPECT_NE(kiosk.state(), State::kOperator);
  EXPECT_TRUE(rig.key(XKB_KEY_F12, DisplayEvent::kCtrl | DisplayEvent::kAlt));
  EXPECT_EQ(kiosk.state(), State::kOperator);
  rig.type("2468\r");
  EXPECT_TRUE(kiosk.operatorPanel().unlocked());
  EXPECT_NE(slurp(rig.dataDir() + "/operator.log").find("Z panel-opened"), std::string::npos);
}

// Opens the operator panel mid-visit and presses C: the calibration screens take over.
void openPanelAndCalibrate(KioskRig& rig) {
  rig.pen().hover(rig.clock().nowNs());
  rig.run(1);
  rig.pen().stroke(rig.clock().nowNs());
  rig.run(3);
  ASSERT_EQ(rig.kiosk().state(), State::kVisitor);
  rig.key('o', DisplayEvent::kCtrl | DisplayEvent::kAlt);
  rig.type("2468\r");
  ASSERT_TRUE(rig.kiosk().operatorPanel().unlocked());
  rig.run(1, 0.0);
  keep("kiosk_operator_panel_before_calibration.png", rig.lastFrame());
  rig.type("c");
  ASSERT_EQ(rig.kiosk().state(), State::kCalibrate);
  ASSERT_NE(rig.kiosk().calibration(), nullptr);
  rig.run(2, 0.0);
  ASSERT_EQ(rig.kiosk().calibration()->stage(), CalibrateFlowScreen::Stage::kTargets)
      << "the scripted tablet is connected: the targets at once";
  keep("kiosk_calibrate_targets.png", rig.lastFrame());
  expectEscGoesBackToThePanel(rig.kiosk().calibration()->words());
}

TEST(KioskScreens, OperatorCalibratesThePenFromThePanel) {
  KioskRig rig("cb_kiosk_calibrate");
  KioskScreen& kiosk = rig.kiosk();
  openPanelAndCalibrate(rig);
  // The pen lands 9 px left of and 5 px below where it is held: the taps on the targets show it.
  const glm::dvec2 error(-9.0, 5.0);
  for (const glm::dvec2& t : targetLayout(9, kW, kH)) {
    rig.pen().tap(t + error, rig.clock().nowNs());
    rig.run(1, 0.2);
  }
  rig.run(1, 0.0);
  ASSERT_EQ(kiosk.state(), State::kCalibrate);
  ASSERT_EQ(kiosk.calibration()->stage(), CalibrateFlowScreen::Stage::kResult);
  keep("kiosk_calibrate_result.png", rig.lastFrame());
  expectEscGoesBackToThePanel(kiosk.calibration()->words());
  const CalibrateBox accept = CalibrateResultScreen::acceptBox(kW, kH);
  rig.pen().tap({accept.x + accept.w / 2, accept.y + accept.h / 2}, rig.clock().nowNs());
  rig.run(2, 0.1);
  // Back on the panel, with the result.
  ASSERT_EQ(kiosk.state(), State::kOperator);
  EXPECT_TRUE(kiosk.operatorPanel().unlocked());
  EXPECT_EQ(kiosk.calibration(), nullptr);
  keep("kiosk_operator_panel_after_calibration.png", rig.lastFrame());
  // The profile is in the data dir (where the kiosk's painter looks), correcting the error.
  const std::string path = rig.dataDir() + "/profiles/056a-fff0.toml";
  ASSERT_TRUE(fs::exists(path)) << "saved inside the data dir";
  ProfileParseResult saved = readCalibrationProfile(path);
  ASSERT_TRUE(saved.profile) << path;
  EXPECT_EQ(saved.profile->fit_kind, PointFitKind::kHomography);
  EXPECT_EQ(saved.profile->fit_points, 9);
  EXPECT_LT(saved.profile->fit_max_px, 0.5);
  for (const glm::dvec2& p : targetLayout(9, kW, kH, 0.0))
    EXPECT_LT(glm::length(applyTransform(saved.profile->correction, p + error) - p), 0.5)
        << p.x << "," << p.y;
  const std::string log = slurp(rig.dataDir() + "/operator.log");
  EXPECT_NE(log.find("Z calibrate started"), std::string::npos) << log;
  EXPECT_NE(log.find("Z calibrate saved " + path + " (homography, 9 points, rms "),
            std::string::npos)
      << log;
  // The visitor's session took the new calibration (journalled with it).
  EXPECT_EQ(kiosk.visitorSession()->calibration().fit_points, 9);
  // Esc closes the panel; the visitor paints on.
  rig.press("esc");
  rig.run(1);
  EXPECT_EQ(kiosk.state(), State::kVisitor);
}

// P on the panel: the press calibration (light, then firm) sets the pressure range for the
// current visitor (journalled, so the visit replays) and for every later visitor, and is kept
// in the data dir for the next start.
TEST(KioskScreens, OperatorCalibratesThePressureFromThePanel) {
  KioskRig rig("cb_kiosk_calibrate_pressure");
  KioskScreen& kiosk = rig.kiosk();
  rig.pen().hover(rig.clock().nowNs());
  rig.run(1);
  ASSERT_EQ(kiosk.state(), State::kVisitor);
  EXPECT_EQ(kiosk.visitorSession()->pressureRange().hi, 1.0f);
  rig.key('o', DisplayEvent::kCtrl | DisplayEvent::kAlt);
  rig.type("2468\r");
  ASSERT_TRUE(kiosk.operatorPanel().unlocked());
  rig.type("p");
  ASSERT_EQ(kiosk.state(), State::kCalibrate);
  rig.run(2, 0.0);
  ASSERT_EQ(kiosk.calibration()->stage(), CalibrateFlowScreen::Stage::kPressure);
  keep("kiosk_calibrate_pressure.png", rig.lastFrame());
  expectEscGoesBackToThePanel(kiosk.calibration()->words());
  rig.pen().press(0.15f, 120, rig.clock().nowNs());  // light
  rig.run(2, 0.7);
  rig.pen().press(0.55f, 120, rig.clock().nowNs());  // firm
  rig.run(3, 0.7);
  ASSERT_EQ(kiosk.state(), State::kOperator) << "back on the panel with the result";
  ASSERT_TRUE(kiosk.pressureRange());
  const PressureRange range = *kiosk.pressureRange();
  EXPECT_NEAR(range.hi, 0.555f, 0.01f);
  EXPECT_NEAR(range.apply(0.15f), 0.2f, 0.03f) << "the light press gives the light target";
  rig.run(1, 0.0);
  keep("kiosk_operator_panel_after_pressure.png", rig.lastFrame());
  // Kept in the data dir; the visitor's session uses it (and journals it).
  const std::string path = rig.dataDir() + "/pressure_range.toml";
  std::string error;
  const std::optional<PressureRange> saved = pressureRangeFromToml(slurp(path), &error);
  ASSERT_TRUE(saved) << path << ": " << error;
  EXPECT_EQ(saved->lo, range.lo);
  EXPECT_EQ(saved->hi, range.hi);
  EXPECT_EQ(kiosk.visitorSession()->pressureRange().lo, range.lo);
  EXPECT_EQ(kiosk.visitorSession()->pressureRange().hi, range.hi);
  const std::string log = slurp(rig.dataDir() + "/operator.log");
  EXPECT_NE(log.find("Z calibrate-pressure started"), std::string::npos) << log;
  EXPECT_NE(log.find("Z calibrate-pressure saved " + path + " (lo "), std::string::npos) << log;
  // The visitor paints on; the next visitor's session starts with the range, journalled.
  rig.press("esc");
  rig.run(1);
  ASSERT_EQ(kiosk.state(), State::kVisitor);
  ASSERT_TRUE(rig.runUntil([&] { return kiosk.state() == State::kAttract; }, 400, 0.5));
  rig.pen().hover(rig.clock().nowNs());
  rig.run(1);
  ASSERT_EQ(kiosk.state(), State::kVisitor);
  EXPECT_EQ(kiosk.visitorSession()->pressureRange().hi, range.hi);
  bool journalled = false;
  for (const auto& entry : fs::directory_iterator(rig.dataDir() + "/sessions")) {
    const std::string text = slurp(entry.path().string());
    journalled = journalled || text.find("pressure_range=") != std::string::npos;
  }
  EXPECT_TRUE(journalled) << "the visitors' journals carry the range";
}

TEST(KioskScreens, EscCancelsTheOperatorsCalibrationAndNothingIsSaved) {
  KioskRig rig("cb_kiosk_calibrate_esc");
  KioskScreen& kiosk = rig.kiosk();
  openPanelAndCalibrate(rig);
  const std::vector<glm::dvec2> targets = targetLayout(9, kW, kH);
  rig.pen().tap(targets[0], rig.clock().nowNs());  // one target tapped, then Esc
  rig.run(1, 0.2);
  rig.press("esc");
  rig.run(2, 0.0);
  EXPECT_EQ(kiosk.state(), State::kOperator) << "Esc cancels the calibration, not the kiosk";
  EXPECT_TRUE(kiosk.operatorPanel().unlocked());
  keep("kiosk_operator_panel_calibration_cancelled.png", rig.lastFrame());
  EXPECT_FALSE(fs::exists(rig.dataDir() + "/profiles"));
  const std::string log = slurp(rig.dataDir() + "/operator.log");
  EXPECT_NE(log.find("Z calibrate cancelled (nothing saved)"), std::string::npos) << log;
  EXPECT_EQ(log.find("Z calibrate saved"), std::string::npos) << log;
}

TEST(KioskScreens, GalleryKeepsFinishedCloudsWithinQuotaAndOldJournalsGo) {
  KioskRig rig(
      "cb_kiosk_gallery",
      [](KioskConfig& c) {
        c.gallery_enabled = true;
        c.gallery_quota_bytes = 1;  // over at once: only the newest entry stays
        c.idle_seconds = 3.0;
        c.warning_seconds = 1.0;
      },
      [](const std::string& data_dir) {
        fs::create_directories(data_dir + "/sessions");
        std::ofstream(data_dir + "/sessions/old.cbj") << "x";
        fs::last_write_time(data_dir + "/sessions/old.cbj",
                            fs::file_time_type::clock::now() - std::chrono::hours(24 * 31));
      });
  KioskScreen& kiosk = rig.kiosk();
  EXPECT_FALSE(fs::exists(rig.dataDir() + "/sessions/old.cbj")) << "older than keep_days";
  rig.pen().hover(rig.clock().nowNs());
  rig.run(1);
  rig.pen().stroke(rig.clock().nowNs());
  rig.run(3);
  const uint64_t painted = volumeChecksum(kiosk.visitorSession()->volume());
  ASSERT_TRUE(rig.runUntil([&] { return kiosk.state() == State::kAttract; }, 60, 0.25));
  ASSERT_EQ(kiosk.gallerySaved(), (std::vector<long>{1}));
  const std::string entry = rig.dataDir() + "/gallery/000001";
  EXPECT_EQ(volumeChecksum(loadVolume(entry + "/cloud.cbvol")), painted);
  EXPECT_EQ(fs::exists(entry + "/cloud.vdb"), volumeExportHasVdb());
  EXPECT_TRUE(fs::exists(entry + "/render.exr"));
  EXPECT_EQ(readPng(entry + "/render.png").width, kW);
  const ImageRgba8 thumbnail = readPng(entry + "/thumbnail.png");
  EXPECT_EQ(thumbnail.width, 320);
  EXPECT_EQ(thumbnail.height, 180);
  keep("kiosk_gallery_thumbnail.png", thumbnail);
  // The next visitor presses "start again" with a cloud painted: kept as number 2, and the
  // quota removes number 1 (oldest first).
  rig.pen().hover(rig.clock().nowNs());
  rig.run(1);
  rig.pen().stroke(rig.clock().nowNs());
  rig.run(3);
  kiosk.onCommand(Command::kDeleteAll, rig.clock().nowNs());
  rig.run(1);
  EXPECT_EQ(kiosk.gallerySaved(), (std::vector<long>{1, 2}));
  EXPECT_EQ(kiosk.notice(), "Your cloud is in the gallery as number 2");
  keep("kiosk_saved_notice.png", rig.lastFrame());
  EXPECT_FALSE(fs::exists(entry)) << "over the quota: the oldest entry went";
  EXPECT_TRUE(fs::exists(rig.dataDir() + "/gallery/000002/thumbnail.png"));
  EXPECT_EQ(density(kiosk.visitorSession()->volume()), 0.0) << "start again cleared the sky";
}

// The data dir on a REAL small file system (a tmpfs, needs root) that something else fills up:
// the kiosk deletes the oldest gallery entry to keep the floor; when even that is not enough it
// keeps painting, saves nothing (no half-written entry, no empty journal), says so on the
// operator panel, to the health file (on_problem / on_storage) and the log; when space returns
// it saves again by itself.
TEST(KioskScreens, AFullDiskKeepsThePaintingSaysSoAndRecovers) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to mount a 64 MB tmpfs as the data dir";
  const std::string name = "cb_kiosk_full_disk";
  std::unique_ptr<test::SmallTmpfs> disk;
  constexpr uint64_t kFloor = 40ull << 20;
  KioskRig rig(
      name,
      [](KioskConfig& c) {
        c.gallery_enabled = true;
        c.min_free_bytes = kFloor;
        c.idle_seconds = 3.0;
        c.warning_seconds = 1.0;
      },
      [&](const std::string& data_dir) {
        disk = std::make_unique<test::SmallTmpfs>(data_dir, 64ull << 20);
        if (!disk->mounted()) throw std::runtime_error(disk->why());
      });
  KioskScreen& kiosk = rig.kiosk();
  const std::string data = rig.dataDir();
  EXPECT_EQ(kiosk.storageProblem(), "");
  paintAVisit(rig);
  ASSERT_EQ(kiosk.gallerySaved(), (std::vector<long>{1}));
  const uint64_t entry_bytes = GalleryStore(data + "/gallery", 0, 0).typicalEntryBytes();
  std::printf("one gallery entry: %.2f MB; the floor %.0f MB on a 64 MB tmpfs\n",
              double(entry_bytes) / 1048576.0, double(kFloor) / 1048576.0);
  ASSERT_LT(entry_bytes + kFloor, 64ull << 20) << "the test's disk is too small for an entry";
  // Something else fills the disk to the last byte.
  disk->fillLeaving(0, data + "/filler");
  ASSERT_LT(disk->freeBytes(), 64u * 1024);
  // The next visitor: entry 1 is deleted for space, still below the floor: no journal.
  rig.pen().hover(rig.clock().nowNs());
  rig.run(1);
  rig.pen().stroke(rig.clock().nowNs());
  rig.run(3);
  EXPECT_EQ(kiosk.state(), State::kVisitor) << "the visitor paints on";
  EXPECT_GT(density(kiosk.visitorSession()->volume()), 0.0);
  EXPECT_FALSE(fs::exists(data + "/gallery/000001")) << "the oldest entry went for space";
  EXPECT_NE(kiosk.storageProblem().find("disk full"), std::string::npos) << kiosk.storageProblem();
  // The operator opens the panel: the disk line says what is not saved.
  rig.key('o', DisplayEvent::kCtrl | DisplayEvent::kAlt);
  rig.type("2468\r");
  rig.run(1);
  ASSERT_EQ(kiosk.state(), State::kOperator);
  keep("kiosk_panel_disk_full.png", rig.lastFrame());
  // ...and how many were lost: health.json's count (visitor 2's journal so far), in red.
  ASSERT_EQ(kiosk.counts().saves_failed, 1);
  EXPECT_EQ(kiosk.operatorPanel().values().saves_failed, kiosk.counts().saves_failed);
  bool count_shown = false;
  for (const UiLabel& label : kiosk.operatorPanel().labels())
    if (label.text.rfind("Not saved since the start: 1 ", 0) == 0)
      count_shown = label.rgba == 0xff8080ffu;
  EXPECT_TRUE(count_shown) << "the panel shows the count of what was not saved, in red";
  rig.key(0xff1b);  // Esc
  rig.run(1);
  ASSERT_TRUE(rig.runUntil([&] { return kiosk.state() == State::kAttract; }, 80, 0.25));
  EXPECT_EQ(kiosk.gallerySaved(), (std::vector<long>{1})) << "nothing more saved";
  EXPECT_EQ(kiosk.savesFailed(), 2) << "the journal and the gallery entry of visitor 2";
  const std::vector<std::string>& problems = rig.problems();
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_NE(problems[0].find("NOT RECORDING visitor 2: disk full"), std::string::npos)
      << problems[0];
  EXPECT_NE(problems[1].find("gallery: NOT SAVED (idle)"), std::string::npos) << problems[1];
  EXPECT_TRUE(filesNamed(data, ".incoming-").empty()) << "no half-written entry";
  EXPECT_TRUE(filesNamed(data, ".tmp.").empty()) << "no temporary file";
  for (const std::string& journal : filesNamed(data + "/sessions", ".cbj"))
    EXPECT_GT(fs::file_size(journal), 0u) << journal << ": no empty journal";
  EXPECT_EQ(filesNamed(data + "/sessions", "-visit2").size(), 0u);
  ASSERT_FALSE(rig.storageStates().empty());
  EXPECT_NE(rig.storageStates().back().find("NOT SAVING"), std::string::npos);
  // Space returns: within the check interval the kiosk says so, and saves the next visitor.
  fs::remove(data + "/filler");
  ASSERT_TRUE(rig.runUntil([&] { return kiosk.storageProblem().empty(); }, 60, 0.5))
      << kiosk.storageProblem();
  EXPECT_EQ(rig.storageStates().back(), "");
  paintAVisit(rig);
  EXPECT_EQ(kiosk.gallerySaved(), (std::vector<long>{1, 2})) << "numbers are not reused";
  EXPECT_TRUE(fs::exists(data + "/gallery/000002/thumbnail.png"));
  EXPECT_EQ(filesNamed(data + "/sessions", "-visit3").size(), 1u);
}

// Retention on the kiosk's clock: with journals and gallery entries kept one day, a visit two
// days later (on the injected clock, seconds of real time) deletes the first visit's journal
// and gallery entry and keeps its own.
TEST(KioskScreens, RetentionAgesFilesOnTheKiosksClock) {
  KioskRig rig("cb_kiosk_retention", [](KioskConfig& c) {
    c.gallery_enabled = true;
    c.gallery_keep_days = 1.0;
    c.journal_keep_days = 1.0;
    c.idle_seconds = 3.0;
    c.warning_seconds = 1.0;
  });
  KioskScreen& kiosk = rig.kiosk();
  const std::string data = rig.dataDir();
  paintAVisit(rig);
  ASSERT_EQ(kiosk.gallerySaved(), (std::vector<long>{1}));
  ASSERT_EQ(filesNamed(data + "/sessions", "-visit1").size(), 1u);
  const std::string journal1 = filesNamed(data + "/sessions", "-visit1")[0];
  // Half a day on: nothing is old enough yet.
  rig.clock().advance(int64_t(0.5 * 86400e9));
  paintAVisit(rig);
  EXPECT_TRUE(fs::exists(journal1));
  EXPECT_TRUE(fs::exists(data + "/gallery/000001"));
  // Two days on: the next visit's end deletes what is older than a day.
  rig.clock().advance(int64_t(2.0 * 86400e9));
  paintAVisit(rig);
  EXPECT_EQ(kiosk.gallerySaved(), (std::vector<long>{1, 2, 3}));
  EXPECT_FALSE(fs::exists(journal1)) << "the first visit's journal, 2.5 days old";
  EXPECT_FALSE(fs::exists(data + "/gallery/000001"));
  EXPECT_FALSE(fs::exists(data + "/gallery/000002"));
  EXPECT_TRUE(fs::exists(data + "/gallery/000003/thumbnail.png")) << "the newest stays";
  EXPECT_EQ(filesNamed(data + "/sessions", "-visit3").size(), 1u);
  EXPECT_TRUE(filesNamed(data + "/sessions", "-visit2").empty());
}

TEST(KioskScreens, ReconnectThePenMidVisitThenPaintOn) {
  KioskRig rig("cb_kiosk_reconnect", [](KioskConfig& c) { c.idle_seconds = 30.0; });
  KioskScreen& kiosk = rig.kiosk();
  // Unplugged while nobody paints: the attract loop goes on.
  rig.pen().unplug();
  rig.run(1);
  EXPECT_EQ(kiosk.state(), State::kAttract);
  rig.pen().replug();
  rig.run(1);
  rig.pen().hover(rig.clock().nowNs());
  rig.run(1);
  rig.pen().stroke(rig.clock().nowNs());
  rig.run(3);
  const uint32_t strokes = kiosk.visitorSession()->strokesMapped();
  EXPECT_EQ(strokes, 1u);
  rig.pen().stroke(rig.clock().nowNs(), /*lift=*/false);  // mid-stroke...
  rig.run(1);
  rig.pen().unplug();  // ...the cable comes out
  rig.run(1);
  ASSERT_EQ(kiosk.state(), State::kReconnect);
  rig.run(5, 1.0);
  EXPECT_EQ(kiosk.state(), State::kReconnect) << "waits for the pen";
  // The tablet is back but the pen lies away from it: the painting returns after a second.
  rig.pen().replug();
  rig.run(1, 0.5);
  EXPECT_EQ(kiosk.state(), State::kReconnect) << "the painting returns with the pen's sample";
  rig.run(2, 0.5);
  EXPECT_EQ(kiosk.state(), State::kVisitor) << "or a second after the replug without one";
  rig.pen().stroke(rig.clock().nowNs());
  rig.run(3);
  EXPECT_GT(kiosk.visitorSession()->strokesMapped(), strokes) << "painting goes on after replug";
  // Twenty more unplug/replug cycles, some mid-stroke: each shows the screen and recovers.
  for (int i = 0; i < 20; ++i) {
    if (i % 2) rig.pen().stroke(rig.clock().nowNs(), /*lift=*/false);
    rig.pen().unplug();
    rig.run(1);
    ASSERT_EQ(kiosk.state(), State::kReconnect) << "cycle " << i;
    rig.pen().replug();
    rig.pen().hover(rig.clock().nowNs());  // the pen near the tablet: back at its first sample
    rig.run(1);
    ASSERT_EQ(kiosk.state(), State::kVisitor) << "cycle " << i;
  }
  const uint32_t before = kiosk.visitorSession()->strokesMapped();
  rig.pen().stroke(rig.clock().nowNs());
  rig.run(3);
  EXPECT_GT(kiosk.visitorSession()->strokesMapped(), before);
}

}  // namespace
}  // namespace cb
