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
#include "app/shell/painter/paint_loop.h"
#include "app/shell/painter/paint_screen.h"
#include "app/shell/ui_overlay.h"
#include "drivers/replay/replay_pen_source.h"

#include "tests/support/recorded_painter.h"
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
  test::RecordedPainter painter;
  ASSERT_TRUE(painter.open({kW, kH, kGrid}, BrushConfig{}, MappingConfig{}, dir + "/session.cbj", 0,
                           &error))
      << error;
  Display& display = *painter.display;
  PaintSession& session = *painter.session;
  const BrushKind first_brush = session.selectedBrush();

  PaintLoopOptions options;
  options.max_frames = 2000;
  options.state_dir = dir + "/state";
  options.config_dir = dir + "/config";
  ASSERT_TRUE(
      parseKeyList("1,p,p,shift+left,shift+right,shift+up,shift+down,up,down,left,right,r,g,space,"
                   "space,2,pageup,pagedown,pageup,minus,"
                   "plus,3,bracketright,bracketleft,b,n,c,c,s,s,4,v,minus,plus,space,v,5,minus,"
                   "plus,delete,ctrl+z,"
                   "ctrl+y,m,m,h,h,ctrl+s,ctrl+o,f,w,d,a,x,t,ctrl+alt+p,ctrl+alt+s,ctrl+alt+a,3",
                   &options.initial_keys, &error))
      << error;
  ReplayOptions replay_options;
  replay_options.realtime = false;
  replay_options.batch = 16;
  ReplayPenSource pen(stroke, replay_options);
  PaintLoop loop(display, painter.renderer, session.volume(), Light{}, options);
  loop.attachPen(&pen, &session);
  PaintLoopSummary summary;
  ASSERT_TRUE(loop.run(nullptr, &summary, &error)) << error;
  EXPECT_EQ(summary.quit_reason, "replay finished");
  painter.journal.close();

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

  const SessionReplay replay =
      replaySession(readJournal(painter.recorded), BrushConfig{}, MappingConfig{});
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
  test::RecordedPainter painter;
  ASSERT_TRUE(painter.open({kW, kH, kGrid}, BrushConfig{}, MappingConfig{}, dir + "/session.cbj", 0,
                           &error))
      << error;
  Display& display = *painter.display;
  PaintSession& session = *painter.session;
  // Where the Light target is: one frame with the menu open.
  float rect[4];
  {
    PaintSession probe({kW, kH, kGrid}, BrushConfig{}, MappingConfig{});
    PaintLoopOptions options;
    options.max_frames = 3;  // ImGui sizes a new window on its first frame, shows it on the next
    options.orbit_degrees_per_second = 0.0f;
    ASSERT_TRUE(parseKeyList("m", &options.initial_keys, &error));
    PaintLoop loop(display, painter.renderer, probe.volume(), Light{}, options);
    loop.attachPen(nullptr, &probe);
    PaintLoopSummary summary;
    ASSERT_TRUE(loop.run(nullptr, &summary, &error)) << error;
    ASSERT_TRUE(loop.screen().ui()) << "the on-screen UI started";
    ASSERT_TRUE(loop.screen().ui()->targetRect(Command::kModeLight, rect));
    if (const char* keep = std::getenv("CB_KEEP_FRAMES"))
      writePng(std::string(keep) + "/menu_probe.png",
               readFramebufferRgba8(display.framebuffer(), kW, kH));
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
  PaintLoopOptions options;
  options.max_frames = 3000;
  options.state_dir = dir + "/state";
  options.config_dir = dir + "/config";
  ASSERT_TRUE(parseKeyList("m", &options.initial_keys, &error));
  ReplayOptions replay_options;
  replay_options.realtime = false;
  replay_options.batch = 2;  // a few samples per frame, as a real pen at 200 Hz and 60 fps
  ReplayPenSource pen(pen_path, replay_options);
  PaintLoop loop(display, painter.renderer, session.volume(), Light{}, options);
  loop.attachPen(&pen, &session);
  PaintLoopSummary summary;
  ASSERT_TRUE(loop.run(nullptr, &summary, &error)) << error;
  painter.journal.close();
  const std::vector<Command>& tapped = loop.screen().tappedCommands();
  EXPECT_NE(std::find(tapped.begin(), tapped.end(), Command::kModeLight), tapped.end())
      << tapped.size() << " taps";
  EXPECT_EQ(session.mode(), Mode::kLight);
  EXPECT_FALSE(loop.screen().menuOpen()) << "a choice closes the menu";
  EXPECT_EQ(session.strokesMapped(), 0u) << "neither the tap nor the light-mode drag painted";
  double density = 0;
  for (float d : session.volume().toDense()) density += d;
  EXPECT_EQ(density, 0.0);
  const SessionReplay replay =
      replaySession(readJournal(painter.recorded), BrushConfig{}, MappingConfig{});
  ASSERT_TRUE(replay.session);
  EXPECT_TRUE(replay.complete());
  EXPECT_EQ(replay.session->mode(), Mode::kLight);
  EXPECT_EQ(replay.session->light().direction, session.light().direction);
  std::filesystem::remove_all(dir);
}

// Camera mode pans: P makes a pen drag pan instead of orbit and Shift+Up pans by keys; the view
// direction and distance stay, the view moves, and each pan is journalled as a typed camera move
// that replays to the same camera.
TEST(PaintScreenCommands, PenDragAndShiftArrowsPanTheViewAndReplay) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("cb_paint_pan_" + std::to_string(::getpid())))
          .string();
  std::filesystem::create_directories(dir + "/state");
  const std::string pen_path = dir + "/pen.cbj";
  {
    PaintSession recorder({kW, kH, kGrid}, BrushConfig{}, MappingConfig{});
    JournalWriter journal;
    ASSERT_TRUE(journal.open(pen_path));
    recorder.recordTo(&journal, 0);
    const PenDeviceInfo tablet = syntheticTablet(kW, kH);
    recorder.setDevice(tablet, 0);
    SyntheticStroke drag;  // a straight drag to the right, a quarter of the screen
    drag.control_points = {{0.4f * kW, 0.5f * kH}, {0.65f * kW, 0.5f * kH}};
    for (const PenSample& s : syntheticPenSamples(drag, tablet, kW, kH, 200.0, 1'000'000'000))
      recorder.feed(s);
  }
  std::string error;
  test::RecordedPainter painter;
  ASSERT_TRUE(painter.open({kW, kH, kGrid}, BrushConfig{}, MappingConfig{}, dir + "/session.cbj", 0,
                           &error))
      << error;
  Display& display = *painter.display;
  PaintSession& session = *painter.session;
  PaintLoopOptions options;
  options.max_frames = 2000;
  options.orbit_degrees_per_second = 0.0f;
  options.state_dir = dir + "/state";
  options.config_dir = dir + "/config";
  ASSERT_TRUE(parseKeyList("1,p,shift+up", &options.initial_keys, &error)) << error;
  ReplayOptions replay_options;
  replay_options.realtime = false;
  replay_options.batch = 4;
  ReplayPenSource pen(pen_path, replay_options);
  const Camera before = session.camera();
  PaintLoop loop(display, painter.renderer, session.volume(), Light{}, options);
  loop.attachPen(&pen, &session);
  PaintLoopSummary summary;
  ASSERT_TRUE(loop.run(nullptr, &summary, &error)) << error;
  painter.journal.close();

  const Camera after = session.camera();
  const glm::vec3 d0 = glm::normalize(before.target - before.eye);
  const glm::vec3 d1 = glm::normalize(after.target - after.eye);
  EXPECT_GT(glm::dot(d0, d1), 0.99999f) << "a pan keeps the view direction";
  EXPECT_NEAR(glm::length(after.eye - after.target), glm::length(before.eye - before.target), 1e-4);
  const glm::vec3 moved = after.target - before.target;
  const glm::vec3 right = glm::normalize(glm::cross(d0, before.up));
  const float step = before.worldPerPixelAtTarget(kH);
  // Shift+Up: the view up by a twentieth of the screen; the drag right: the view left by the
  // drag's length (the scene follows the pen).
  EXPECT_NEAR(glm::dot(moved, glm::cross(right, d0)), 0.05f * kH * step, 0.02f * kH * step);
  EXPECT_LT(glm::dot(moved, right), -0.15f * kW * step);
  EXPECT_GT(glm::dot(moved, right), -0.3f * kW * step);

  int pans = 0;
  for (const JournalRecord& r : readJournal(painter.recorded).records)
    if (r.type == JournalRecordType::kUi) {
      UiChange change;
      std::string why;
      if (parseUiChange(r.type, r.text(), &change, &why) &&
          std::holds_alternative<ui::SetCamera>(change))
        pans += std::get<ui::SetCamera>(change).move == CameraMove::kPan;
    }
  EXPECT_EQ(pans, 2) << "one for the key, one for the drag";
  const SessionReplay replay =
      replaySession(readJournal(painter.recorded), BrushConfig{}, MappingConfig{});
  ASSERT_TRUE(replay.session);
  EXPECT_TRUE(replay.complete());
  EXPECT_EQ(replay.session->camera().eye, after.eye);
  EXPECT_EQ(replay.session->camera().target, after.target);
  std::filesystem::remove_all(dir);
}

// Erase mode, Vacuum: the pen hovering over the canvas places the sphere, drawn with its rod and
// the grids of the three axis planes through its centre (§3.5.1, Fig. 3.5). The green plane's
// lines show where the sky is otherwise bluer than green.
TEST(PaintScreenCommands, VacuumShowsTheAxisPlaneGrids) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("cb_paint_vacuum_" + std::to_string(::getpid())))
          .string();
  std::filesystem::create_directories(dir + "/state");
  const std::string pen_path = dir + "/pen.cbj";
  {
    JournalWriter journal;
    ASSERT_TRUE(journal.open(pen_path));
    const PenDeviceInfo tablet = syntheticTablet(kW, kH);
    const auto bytes = encodeDeviceInfo(tablet);
    journal.append(JournalRecordType::kDevice, 0, bytes.data(), bytes.size());
    SyntheticStroke hover;  // the pen hovers across the middle of the screen, never touching
    hover.control_points = {{0.45f * kW, 0.55f * kH}, {0.55f * kW, 0.55f * kH}};
    for (PenSample s : syntheticPenSamples(hover, tablet, kW, kH, 200.0, 1'000'000'000)) {
      s.pressure = 0.0f;
      s.pressure_raw = 0;
      s.buttons &= ~uint32_t(kPenTip);
      s.in_proximity = true;
      journal.appendPenSample(s);
    }
  }
  std::string error;
  std::unique_ptr<Display> display = test::openTestDisplay(kW, kH, &error);
  ASSERT_TRUE(display) << error;
  VolumeRenderer renderer;
  ASSERT_TRUE(renderer.init(&error)) << error;
  const auto greenish = [&](const ImageRgba8& image) {
    long n = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) n += image.at(x, y)[1] > image.at(x, y)[2] + 10;
    return n;
  };
  long counts[2] = {0, 0};
  for (int vacuum = 0; vacuum < 2; ++vacuum) {
    PaintSession session({kW, kH, kGrid}, BrushConfig{}, MappingConfig{});
    session.setQuietMapping(true);
    PaintLoopOptions options;
    options.max_frames = 400;
    options.orbit_degrees_per_second = 0.0f;
    options.state_dir = dir + "/state";
    options.config_dir = dir + "/config";
    ASSERT_TRUE(parseKeyList(vacuum ? "4,v" : "4", &options.initial_keys, &error)) << error;
    ImageRgba8 last;
    options.on_frame = [&](const PaintFrameInfo&) {
      last = readFramebufferRgba8(display->framebuffer(), kW, kH);
    };
    ReplayOptions replay_options;
    replay_options.realtime = false;
    replay_options.batch = 4;
    ReplayPenSource pen(pen_path, replay_options);
    PaintLoop loop(*display, renderer, session.volume(), Light{}, options);
    loop.attachPen(&pen, &session);
    PaintLoopSummary summary;
    ASSERT_TRUE(loop.run(nullptr, &summary, &error)) << error;
    EXPECT_EQ(session.eraseTool(), vacuum ? EraseTool::kVacuum : EraseTool::kRubOut);
    counts[vacuum] = greenish(last);
    if (const char* keep = std::getenv("CB_KEEP_FRAMES"))
      writePng(std::string(keep) + (vacuum ? "/erase_vacuum.png" : "/erase_rubout.png"), last);
  }
  std::printf("greener-than-blue pixels: rub-out %ld, vacuum %ld\n", counts[0], counts[1]);
  EXPECT_LT(counts[0], 50) << "the sky alone is bluer than green";
  EXPECT_GT(counts[1], 300) << "the green plane's grid lines";
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cb
