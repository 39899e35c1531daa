// Dragging the light ball with the mouse (Light mode, key 5): while it moves the frames read the
// drag's coarse light (reduced_light_sweep.h) and the renderer's light volume stays the one before
// the drag (nothing swept in full, nothing re-packed); the release sweeps it in full for the light
// journalled, and the journal replays to that light.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>

#include "app/session/paint_session.h"
#include "app/session/session_replay.h"
#include "app/shell/painter/paint_loop.h"
#include "app/volume/scene_generators.h"
#include "drivers/core/journal.h"
#include "drivers/core/no_pen_source.h"
#include "tests/support/recorded_painter.h"
#include "tests/support/test_display.h"

namespace cb {
namespace {

constexpr int kW = 320, kH = 180, kGrid = 64;
constexpr int kDragFrom = 4, kDragTo = 12;  // the frames the button is held over

TEST(LightDrag, FramesReadTheCoarseLightAndTheReleaseSweepsInFull) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("cb_light_drag_" + std::to_string(::getpid())))
          .string();
  std::filesystem::create_directories(dir + "/state");
  std::string error;
  test::RecordedPainter painter;
  ASSERT_TRUE(painter.open({kW, kH, kGrid}, BrushConfig{}, MappingConfig{}, dir + "/session.cbj", 0,
                           &error))
      << error;
  Display& display = *painter.display;
  PaintSession& session = *painter.session;
  ASSERT_TRUE(session.replaceVolume(makeBundledCumulus(glm::ivec3(kGrid), 1), 0, "cumulus", &error))
      << error;
  const Light before = session.light();
  VolumeRenderer& renderer = painter.renderer;

  std::atomic<bool> stop{false};
  int frame = 0, previewed = 0, swept_during_drag = 0, preview_after_release = 0;
  const auto pointer = [&](DisplayEvent::Kind kind, int i) {
    const float a = 0.4f * float(i);
    DisplayEvent e;
    e.kind = kind;
    e.x = kW * (0.5f + 0.25f * std::cos(a));
    e.y = kH * (0.3f + 0.15f * std::sin(a));
    e.button = 1;
    display.injectEvent(e);
  };
  PaintLoopOptions options;
  options.max_frames = 200;
  options.state_dir = dir + "/state";
  options.config_dir = dir + "/config";
  options.on_frame = [&](const PaintFrameInfo&) {
    ++frame;
    if (frame == 2) display.injectEvent(DisplayEvent::key('5'));
    if (frame == kDragFrom) pointer(DisplayEvent::Kind::PointerMove, frame);
    if (frame == kDragFrom) pointer(DisplayEvent::Kind::PointerDown, frame);
    if (frame > kDragFrom && frame < kDragTo) pointer(DisplayEvent::Kind::PointerMove, frame);
    if (frame > kDragFrom + 1 && frame <= kDragTo) {
      previewed += renderer.lightIsPreview();
      swept_during_drag += renderer.lightVolume().matches(session.volume(), before) ? 0 : 1;
    }
    if (frame == kDragTo) pointer(DisplayEvent::Kind::PointerUp, frame);
    if (frame > kDragTo + 1) preview_after_release += renderer.lightIsPreview();
    if (frame == kDragTo + 6) stop = true;
  };
  PaintLoop loop(display, renderer, session.volume(), Light{}, options);
  NoPenSource no_tablet;
  loop.attachPen(&no_tablet, &session);
  PaintLoopSummary summary;
  ASSERT_TRUE(loop.run(&stop, &summary, &error)) << error;
  painter.journal.close();

  EXPECT_EQ(session.mode(), Mode::kLight);
  EXPECT_GT(glm::length(session.light().direction - before.direction), 0.05f)
      << "the drag turned the light";
  EXPECT_EQ(previewed, kDragTo - kDragFrom - 1) << "every drag frame read the coarse light";
  EXPECT_EQ(swept_during_drag, 0) << "the light volume kept the light before the drag";
  EXPECT_EQ(preview_after_release, 0);
  EXPECT_TRUE(renderer.lightVolume().matches(session.volume(), session.light()))
      << "the release swept the light volume for the light journalled";
  const SessionReplay replay =
      replaySession(readJournal(painter.recorded), BrushConfig{}, MappingConfig{});
  ASSERT_TRUE(replay.session);
  EXPECT_EQ(replay.session->light().direction, session.light().direction);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cb
