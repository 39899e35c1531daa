// Morph and wind in the painter, through the real shell on EGL surfaceless (llvmpipe): Ctrl+O
// opens a saved cloud, a mouse tap on the pen menu's Morph target starts the morph, A applies it
// half way; a tap on Wind starts the wind and a second tap stops it, X leaves it (the cloud as it
// was), W blows again and A applies. The session ends with two more history steps, its journal
// replays to the same volume on 1 and 8 threads. CB_KEEP_FRAMES=DIR keeps a morph and a wind
// frame and the menu with its animation row.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <functional>

#include <gtest/gtest.h>
#include <xkbcommon/xkbcommon-keysyms.h>

#include "app/core/parallel_for.h"
#include "app/render/image_io.h"
#include "app/session/paint_session.h"
#include "app/session/session_replay.h"
#include "app/shell/keymap.h"
#include "app/shell/painter/animation_preview.h"
#include "app/shell/painter/paint_loop.h"
#include "app/shell/painter/paint_screen.h"
#include "app/shell/ui_overlay.h"
#include "app/volume/scene_generators.h"
#include "app/volume/volume_file.h"

#include "tests/support/recorded_painter.h"
#include "tests/support/test_display.h"

namespace cb {
namespace {

constexpr int kW = 480, kH = 270, kGrid = 128;

void keep(const char* name, const Display& display) {
  if (const char* dir = std::getenv("CB_KEEP_FRAMES"))
    writePng(std::string(dir) + "/" + name, readFramebufferRgba8(display.framebuffer(), kW, kH));
}

// The script, one stage at a time, run after each frame is drawn: what it taps and presses, and
// the checksums of the cloud opened, the morph applied and the wind applied.
class AnimationScript {
 public:
  AnimationScript(Display& display, const PaintSession& session)
      : display_(display), session_(session) {}
  void watch(const PaintScreen* screen) { screen_ = screen; }

  void onFrame() {
    ++frames_in_stage_;
    switch (stage_) {
      case 0:  // the menu is open on the opened cloud: tap Morph
        if (frames_in_stage_ == 3) {
          opened = volumeChecksum(session_.volume());
          steps_opened = session_.history().steps();
          keep("animation_menu.png", display_);
          if (tap(Command::kMorph)) next();
        }
        break;
      case 1:  // the morph plays; half way, A applies what is shown
        morphHalfWay();
        break;
      case 2:  // applied: open the menu again
        if (frames_in_stage_ == 1) key('m');
        if (frames_in_stage_ == 4 && tap(Command::kWind)) next();
        break;
      case 3:  // the wind blows; after some steps the menu's Wind target stops it
        if (frames_in_stage_ == 1) key('d');  // towards the north-east
        if (frames_in_stage_ == 12) {
          keep("animation_wind.png", display_);
          key('m');
        }
        if (frames_in_stage_ == 15 && tap(Command::kWind)) next();
        break;
      case 4:
        windStoppedLeftAndApplied();
        break;
    }
  }
  int stage() const { return stage_; }

  size_t steps_opened = 0;
  uint64_t opened = 0, morphed = 0, blown = 0;
  bool menu_stopped_wind = false;

 private:
  void morphHalfWay() {
    const AnimationPreview* a = screen_->animation();
    if (!(a && a->active() && a->morphT() >= 0.5f)) return;
    keep("animation_morph.png", display_);
    morphed = volumeChecksum(withFrame(session_.volume(), a->fullFrame(session_)));
    EXPECT_TRUE(a->atHalfResolution()) << "a 128³ cloud animates at 64³";
    key('a');
    next();
  }
  // Stopped by the menu; X leaves it, then W blows again and A applies.
  void windStoppedLeftAndApplied() {
    const AnimationPreview* a = screen_->animation();
    const auto& tapped = screen_->tappedCommands();
    if (std::count(tapped.begin(), tapped.end(), Command::kWind) < 2) {
      frames_in_stage_ = 0;  // the tap is still on its way through the UI
      return;
    }
    if (frames_in_stage_ == 1) {
      menu_stopped_wind = a && a->active() && !a->playing();
      key('m');  // the menu again, so frames keep coming while nothing moves
      key('x');
    }
    if (frames_in_stage_ == 2) key('w');
    if (frames_in_stage_ == 8 && a && a->playing()) {
      blown = volumeChecksum(withFrame(session_.volume(), a->fullFrame(session_)));
      key('a');
    }
    if (frames_in_stage_ == 10) {
      // In one go: with the menu closed nothing moves and no frame comes to script more.
      key(XKB_KEY_Escape);  // Esc closes the open menu first,
      key(XKB_KEY_Escape);  // then asks (unsaved work),
      key(XKB_KEY_Escape);  // and Esc again quits
    }
  }
  bool tap(Command command) {
    float r[4];
    if (!screen_->ui() || !screen_->ui()->targetRect(command, r)) return false;
    DisplayEvent e;
    e.x = 0.5f * (r[0] + r[2]);
    e.y = 0.5f * (r[1] + r[3]);
    e.button = 1;
    for (DisplayEvent::Kind kind :
         {DisplayEvent::Kind::PointerMove, DisplayEvent::Kind::PointerDown,
          DisplayEvent::Kind::PointerUp}) {
      e.kind = kind;
      display_.injectEvent(e);
    }
    return true;
  }
  void key(uint32_t keysym) { display_.injectEvent(DisplayEvent::key(keysym)); }
  void next() {
    ++stage_;
    frames_in_stage_ = 0;
  }

  Display& display_;
  const PaintSession& session_;
  const PaintScreen* screen_ = nullptr;  // set once the loop exists
  int stage_ = 0, frames_in_stage_ = 0;
};

// After the script: the session's history undoes to the morph and to the opened cloud, and its
// journal replays to the wind's cloud on 1 and 8 threads.
void expectHistoryAndReplay(PaintSession& session, const AnimationScript& script,
                            const std::string& recorded) {
  std::string error;
  EXPECT_EQ(session.history().steps(), script.steps_opened + 2) << "one step per apply";
  EXPECT_EQ(volumeChecksum(session.volume()), script.blown) << "the wind shown was applied";
  // Undo the wind: the morph's frame as applied (the left wind did not touch it).
  ASSERT_TRUE(session.apply(ui::Undo{}, 0, &error)) << error;
  EXPECT_EQ(volumeChecksum(session.volume()), script.morphed);
  ASSERT_TRUE(session.apply(ui::Undo{}, 0, &error)) << error;
  EXPECT_EQ(volumeChecksum(session.volume()), script.opened);
  ASSERT_TRUE(session.apply(ui::Redo{}, 0, &error)) << error;
  ASSERT_TRUE(session.apply(ui::Redo{}, 0, &error)) << error;

  const JournalReadResult read = readJournal(recorded);
  for (int threads : {1, 8}) {
    setWorkerThreads(threads);
    const SessionReplay replay = replaySession(read, BrushConfig{}, MappingConfig{});
    ASSERT_TRUE(replay.session);
    EXPECT_TRUE(replay.complete())
        << (replay.problems.empty() ? replay.journal_error : replay.problems[0]);
    EXPECT_EQ(volumeChecksum(replay.session->volume()), script.blown) << threads << " threads";
  }
  setWorkerThreads(0);
}

TEST(AnimationPainter, TheMenuStartsAndStopsMorphAndWindAndApplyReplays) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("cb_anim_painter_" + std::to_string(::getpid())))
          .string();
  std::filesystem::create_directories(dir + "/state");
  saveVolume(makeBundledCumulus(glm::ivec3(kGrid), 1), dir + "/state/source.vol");
  // The target: the cumulus's puffs somewhere else (a different cloud of the same sky).
  saveVolume(makeSparsePuffs(glm::ivec3(kGrid), 5), dir + "/target.vol");

  std::string error;
  test::RecordedPainter painter;
  ASSERT_TRUE(painter.open({kW, kH, kGrid}, BrushConfig{}, MappingConfig{}, dir + "/session.cbj", 0,
                           &error))
      << error;
  Display& display = *painter.display;
  PaintSession& session = *painter.session;

  PaintLoopOptions options;
  options.max_frames = 400;
  options.orbit_degrees_per_second = 0.0f;
  options.state_dir = dir + "/state";
  options.config_dir = dir + "/config";
  options.morph_target = dir + "/target.vol";
  options.morph_seconds = 1.0;
  ASSERT_TRUE(parseKeyList("ctrl+o,m", &options.initial_keys, &error)) << error;
  AnimationScript script(display, session);
  options.on_frame = [&script](const PaintFrameInfo&) { script.onFrame(); };
  PaintLoop loop(display, painter.renderer, session.volume(), Light{}, options);
  loop.attachPen(nullptr, &session);
  const PaintScreen* screen = &loop.screen();
  script.watch(screen);
  PaintLoopSummary summary;
  ASSERT_TRUE(loop.run(nullptr, &summary, &error)) << error;
  painter.journal.close();

  EXPECT_EQ(script.stage(), 4) << "the script ran to its end (stage " << script.stage() << ")";
  EXPECT_EQ(summary.quit_reason, "Esc");
  const std::vector<Command>& tapped = screen->tappedCommands();
  EXPECT_EQ(std::count(tapped.begin(), tapped.end(), Command::kMorph), 1);
  EXPECT_EQ(std::count(tapped.begin(), tapped.end(), Command::kWind), 2)
      << "the menu started and stopped the wind";
  EXPECT_TRUE(script.menu_stopped_wind);
  EXPECT_NE(script.opened, 0u);
  EXPECT_NE(script.morphed, script.opened) << "the morph moved the cloud";
  EXPECT_FALSE(screen->animation()->active());
  expectHistoryAndReplay(session, script, painter.recorded);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cb
