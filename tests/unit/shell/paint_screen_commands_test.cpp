// Every command reaches the painter through the one frame loop: keys injected on the surfaceless
// display go through the keymap to PaintScreen, change the session (journalled), and a stroke
// from the replay pen is then painted in the state they left; the journal replays to the same
// volume.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include "app/render/image_io.h"
#include "app/session/paint_session.h"
#include "app/session/session_replay.h"
#include "app/session/synthetic_session.h"
#include "app/shell/keymap.h"
#include "app/shell/paint_loop.h"
#include "app/shell/paint_screen.h"
#include "app/shell/ui_overlay.h"
#include "drivers/replay/replay_pen_source.h"

#include "tests/support/test_display.h"

namespace cb {
namespace {

constexpr int kW = 320, kH = 180, kGrid = 64;

TEST(PaintScreenCommands, EveryCommandKeyIsRoutedAndTheJournalReplays) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("cb_paint_commands_" + std::to_string(::getpid())))
          .string();
  std::filesystem::create_directories(dir + "/state");
  // The pen: one reference stroke.
  const std::string stroke = dir + "/stroke.cbj";
  {
    PaintSession recorder({kW, kH, kGrid}, BrushConfig{}, MappingConfig{});
    recorder.setQuietMapping(true);
    JournalWriter journal;
    ASSERT_TRUE(journal.open(stroke));
    recorder.recordTo(&journal, 0);
    const PenDeviceInfo tablet = syntheticTablet(kW, kH);
    recorder.setDevice(tablet, 0);
    for (const PenSample& s : syntheticPenSamples(referencePaintStrokes(kW, kH)[0], tablet, kW, kH,
                                                  200.0, 1'000'000'000))
      recorder.feed(s);
  }
  std::string error;
  std::unique_ptr<Display> display = test::openTestDisplay(kW, kH, &error);
  ASSERT_TRUE(display) << error;
  VolumeRenderer renderer;
  ASSERT_TRUE(renderer.init(&error)) << error;
  PaintSession session({kW, kH, kGrid}, BrushConfig{}, MappingConfig{});
  session.setQuietMapping(true);
  const std::string recorded = dir + "/session.cbj";
  JournalWriter journal;
  ASSERT_TRUE(journal.open(recorded));
  session.recordTo(&journal, 0);
  const BrushKind first_brush = session.selectedBrush();

  PaintLoopOptions options;
  options.max_frames = 2000;
  options.state_dir = dir + "/state";
  options.config_dir = dir + "/config";
  ASSERT_TRUE(
      parseKeyList("1,up,down,left,right,r,g,space,space,2,pageup,pagedown,pageup,minus,"
                   "plus,3,b,n,c,c,s,s,4,v,minus,plus,space,v,5,minus,plus,delete,ctrl+z,"
                   "ctrl+y,m,m,ctrl+s,ctrl+o,f,w,d,a,x,t,3",
                   &options.initial_keys, &error))
      << error;
  ReplayOptions replay_options;
  replay_options.realtime = false;
  replay_options.batch = 16;
  ReplayPenSource pen(stroke, replay_options);
  PaintLoop loop(*display, renderer, session.volume(), Light{}, options);
  loop.attachPen(&pen, &session);
  PaintLoopSummary summary;
  ASSERT_TRUE(loop.run(nullptr, &summary, &error)) << error;
  EXPECT_EQ(summary.quit_reason, "replay finished");
  journal.close();

  std::set<std::string> routed(loop.routedCommands().begin(), loop.routedCommands().end());
  for (int i = 0; i < int(Command::kCount); ++i) {
    const char* name = commandName(Command(i));
    if (Command(i) == Command::kQuit) continue;  // pressed by the display tests (Esc, q)
    EXPECT_TRUE(routed.count(name)) << name << " was not routed";
  }
  // The state the keys left, then the stroke painted in it.
  EXPECT_EQ(session.mode(), Mode::kPaint);
  EXPECT_NE(session.selectedBrush(), first_brush);
  EXPECT_EQ(session.mappingMethod(), MappingMethod::kRayMarching);
  EXPECT_FLOAT_EQ(session.canvas().altitude, session.volume().voxelSize().y);
  EXPECT_EQ(session.strokesMapped(), 1u);
  EXPECT_EQ(summary.strokes_mapped, 1);
  bool saved = false;
  for (const auto& entry : std::filesystem::directory_iterator(dir + "/state"))
    saved |= entry.path().extension() == ".vol";
  EXPECT_TRUE(saved) << "Ctrl+S saved the cloud";

  const SessionReplay replay = replaySession(readJournal(recorded), BrushConfig{}, MappingConfig{});
  ASSERT_TRUE(replay.session);
  EXPECT_TRUE(replay.complete()) << replay.journal_error
                                 << (replay.problems.empty() ? "" : replay.problems[0]);
  EXPECT_EQ(volumeChecksum(replay.session->volume()), volumeChecksum(session.volume()));
  EXPECT_EQ(session.styleName(), "physical") << "T chose the next render style";
  EXPECT_EQ(replay.session->styleName(), "physical") << "the style is journalled";
  std::filesystem::remove_all(dir);
}

// The pen menu: M opens it, a pen tap on the Light target switches the mode (and closes the
// menu) without painting a dot; the stroke that follows paints nothing in Light mode; the
// journal replays to the same state.
TEST(PaintScreenCommands, APenTapOnTheMenuChoosesAModeAndPaintsNothing) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("cb_paint_menu_" + std::to_string(::getpid())))
          .string();
  std::filesystem::create_directories(dir + "/state");
  std::string error;
  std::unique_ptr<Display> display = test::openTestDisplay(kW, kH, &error);
  ASSERT_TRUE(display) << error;
  VolumeRenderer renderer;
  ASSERT_TRUE(renderer.init(&error)) << error;
  // Where the Light target is: one frame with the menu open.
  float rect[4];
  {
    PaintSession probe({kW, kH, kGrid}, BrushConfig{}, MappingConfig{});
    PaintLoopOptions options;
    options.max_frames = 3;  // ImGui sizes a new window on its first frame, shows it on the next
    options.orbit_degrees_per_second = 0.0f;
    ASSERT_TRUE(parseKeyList("m", &options.initial_keys, &error));
    PaintLoop loop(*display, renderer, probe.volume(), Light{}, options);
    loop.attachPen(nullptr, &probe);
    PaintLoopSummary summary;
    ASSERT_TRUE(loop.run(nullptr, &summary, &error)) << error;
    ASSERT_TRUE(loop.screen().ui()) << "the on-screen UI started";
    ASSERT_TRUE(loop.screen().ui()->targetRect(Command::kModeLight, rect));
    if (const char* keep = std::getenv("CB_KEEP_FRAMES"))
      writePng(std::string(keep) + "/menu_probe.png",
               readFramebufferRgba8(display->framebuffer(), kW, kH));
  }
  std::printf("light target %g,%g - %g,%g\n", rect[0], rect[1], rect[2], rect[3]);
  const glm::vec2 light_target(0.5f * (rect[0] + rect[2]), 0.5f * (rect[1] + rect[3]));
  // The pen: a tap on the target, then a stroke across the screen.
  const std::string pen_path = dir + "/pen.cbj";
  {
    PaintSession recorder({kW, kH, kGrid}, BrushConfig{}, MappingConfig{});
    JournalWriter journal;
    ASSERT_TRUE(journal.open(pen_path));
    recorder.recordTo(&journal, 0);
    const PenDeviceInfo tablet = syntheticTablet(kW, kH);
    recorder.setDevice(tablet, 0);
    SyntheticStroke tap;
    tap.control_points = {light_target, light_target + glm::vec2(1.0f, 0.0f)};
    int64_t t = 1'000'000'000;
    for (const SyntheticStroke& s : {tap, referencePaintStrokes(kW, kH)[0]})
      for (const PenSample& sample : syntheticPenSamples(s, tablet, kW, kH, 200.0, t)) {
        recorder.feed(sample);
        t = sample.t_ns + 1'000'000;
      }
  }
  PaintSession session({kW, kH, kGrid}, BrushConfig{}, MappingConfig{});
  session.setQuietMapping(true);
  const std::string recorded = dir + "/session.cbj";
  JournalWriter journal;
  ASSERT_TRUE(journal.open(recorded));
  session.recordTo(&journal, 0);
  PaintLoopOptions options;
  options.max_frames = 3000;
  options.state_dir = dir + "/state";
  options.config_dir = dir + "/config";
  ASSERT_TRUE(parseKeyList("m", &options.initial_keys, &error));
  ReplayOptions replay_options;
  replay_options.realtime = false;
  replay_options.batch = 2;  // a few samples per frame, as a real pen at 200 Hz and 60 fps
  ReplayPenSource pen(pen_path, replay_options);
  PaintLoop loop(*display, renderer, session.volume(), Light{}, options);
  loop.attachPen(&pen, &session);
  PaintLoopSummary summary;
  ASSERT_TRUE(loop.run(nullptr, &summary, &error)) << error;
  journal.close();
  const std::vector<Command>& tapped = loop.screen().tappedCommands();
  EXPECT_NE(std::find(tapped.begin(), tapped.end(), Command::kModeLight), tapped.end())
      << tapped.size() << " taps";
  EXPECT_EQ(session.mode(), Mode::kLight);
  EXPECT_FALSE(loop.screen().menuOpen()) << "a choice closes the menu";
  EXPECT_EQ(session.strokesMapped(), 0u) << "neither the tap nor the light-mode drag painted";
  double density = 0;
  for (size_t i = 0; i < session.volume().voxelCount(); ++i) density += session.volume().data()[i];
  EXPECT_EQ(density, 0.0);
  const SessionReplay replay = replaySession(readJournal(recorded), BrushConfig{}, MappingConfig{});
  ASSERT_TRUE(replay.session);
  EXPECT_TRUE(replay.complete());
  EXPECT_EQ(replay.session->mode(), Mode::kLight);
  EXPECT_EQ(replay.session->light().direction, session.light().direction);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cb
