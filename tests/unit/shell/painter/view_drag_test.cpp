// Dragging the light ball with the mouse (Light mode, key 5): while it moves the frames read the
// drag's coarse light (reduced_light_sweep.h) and the renderer's light volume stays the one before
// the drag (nothing swept in full, nothing re-packed); the release sweeps it in full for the light
// journalled, and the journal replays to that light. Dragging the view round (Camera mode, key
// 1): its frames are the painter's moving frames (moving_frames.h), and at rest the view is cast
// in full again whichever way they were drawn.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <functional>
#include <vector>

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

// A recorded painter over the bundled cumulus in a temporary folder of its own, and the loop
// options every run here uses.
struct CumulusPainter {
  std::string dir;
  test::RecordedPainter painter;
  explicit CumulusPainter(const std::string& name)
      : dir((std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid())))
                .string()) {
    std::filesystem::create_directories(dir + "/state");
  }
  ~CumulusPainter() { std::filesystem::remove_all(dir); }
  bool open(std::string* error) {
    return painter.open({kW, kH, kGrid}, BrushConfig{}, MappingConfig{}, dir + "/session.cbj", 0,
                        error) &&
           painter.session->replaceVolume(makeBundledCumulus(glm::ivec3(kGrid), 1), 0, "cumulus",
                                          error);
  }
  PaintLoopOptions options() const {
    PaintLoopOptions o;
    o.max_frames = 200;
    o.state_dir = dir + "/state";
    o.config_dir = dir + "/config";
    // A ray per pixel at rest: these tests tell a drag's frames from the frame at rest by their
    // cast's width (CameraDrag checks the painter's default, the rest cast at the volume's detail).
    o.cast_at_volume_detail = false;
    return o;
  }
};

TEST(LightDrag, FramesReadTheCoarseLightAndTheReleaseSweepsInFull) {
  CumulusPainter fixture("cb_light_drag");
  std::string error;
  ASSERT_TRUE(fixture.open(&error)) << error;
  test::RecordedPainter& painter = fixture.painter;
  Display& display = *painter.display;
  PaintSession& session = *painter.session;
  const Light before = session.light();
  VolumeRenderer& renderer = painter.renderer;

  std::atomic<bool> stop{false};
  int frame = 0, previewed = 0, swept_during_drag = 0, preview_after_release = 0;
  const auto pointer = [&](DisplayEvent::Kind kind, int i) {
    const float a = 0.4f * float(i);
    display.injectEvent(DisplayEvent::pointer(kind, kW * (0.5f + 0.25f * std::cos(a)),
                                              kH * (0.3f + 0.15f * std::sin(a))));
  };
  PaintLoopOptions options = fixture.options();
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
}

// The light drag keeps to its frame budget by its own resolution scale: over budget every drag
// frame shrinks it by a tenth down to min_light_drag_scale, under budget it grows back no
// further than the moving scale; the release's frame still shows the coarse light at that scale,
// and the frame after it is cast at full resolution with the light swept in full.
struct DragRun {
  std::vector<int> drag_widths;  // the cast image's width on each drag frame
  int release_width = 0;         // on the frame the release was shown
  bool release_preview = false;  // that frame still read the coarse light
  int full_width = 0;            // on the frame after it
  bool full_preview = true;
};

// A mouse drag scripted frame by frame in the painter over the fixture's cumulus: `mode_key` at
// frame 2, the button pressed at kDragFrom, moved right by `dx` of the width a frame from x0 at
// height y (fractions of the screen) and released at kDragTo; `each` sees every frame (and may
// stop the loop). Returns the loop's summary.
PaintLoopSummary runScriptedDrag(CumulusPainter& fixture, PaintLoopOptions options, char mode_key,
                                 float x0, float dx, float y,
                                 const std::function<void(int, std::atomic<bool>&)>& each) {
  test::RecordedPainter& painter = fixture.painter;
  Display& display = *painter.display;
  PaintSession& session = *painter.session;
  std::atomic<bool> stop{false};
  int frame = 0;
  const auto pointer = [&](DisplayEvent::Kind kind, int i) {
    display.injectEvent(DisplayEvent::pointer(kind, kW * (x0 + dx * float(i)), kH * y));
  };
  options.on_frame = [&](const PaintFrameInfo&) {
    ++frame;
    if (frame == 2) display.injectEvent(DisplayEvent::key(mode_key));
    each(frame, stop);
    if (frame == kDragFrom) pointer(DisplayEvent::Kind::PointerMove, frame);
    if (frame == kDragFrom) pointer(DisplayEvent::Kind::PointerDown, frame);
    if (frame > kDragFrom && frame < kDragTo) pointer(DisplayEvent::Kind::PointerMove, frame);
    if (frame == kDragTo) pointer(DisplayEvent::Kind::PointerUp, kDragTo - 1);
  };
  PaintLoop loop(display, painter.renderer, session.volume(), Light{}, options);
  NoPenSource no_tablet;
  loop.attachPen(&no_tablet, &session);
  PaintLoopSummary summary;
  std::string error;
  EXPECT_TRUE(loop.run(&stop, &summary, &error)) << error;
  painter.journal.close();
  return summary;
}

DragRun runDrag(double frame_budget_ms, const std::string& name) {
  DragRun run;
  CumulusPainter fixture(name);
  std::string error;
  EXPECT_TRUE(fixture.open(&error)) << error;
  if (!fixture.painter.display) return run;
  const VolumeRenderer& renderer = fixture.painter.renderer;
  PaintLoopOptions options = fixture.options();
  options.light_drag_frame_ms = frame_budget_ms;
  runScriptedDrag(fixture, options, '5', 0.3f, 0.03f, 0.3f,
                  [&](int frame, std::atomic<bool>& stop) {
                    if (frame > kDragFrom && frame <= kDragTo)
                      run.drag_widths.push_back(renderer.lastStats().width);
                    if (frame == kDragTo + 1) {
                      run.release_width = renderer.lastStats().width;
                      run.release_preview = renderer.lightIsPreview();
                    }
                    if (frame == kDragTo + 2) {
                      run.full_width = renderer.lastStats().width;
                      run.full_preview = renderer.lightIsPreview();
                      stop = true;
                    }
                  });
  return run;
}

TEST(LightDrag, ItsScaleKeepsToTheFrameBudget) {
  const PaintLoopOptions defaults;
  const int moving = int(std::lround(kW * defaults.moving_scale));
  const int floor = int(std::lround(kW * defaults.min_light_drag_scale));
  // No frame can meet a budget of a microsecond: the scale shrinks to its floor and stays.
  const DragRun over = runDrag(0.001, "cb_light_drag_over");
  ASSERT_EQ(over.drag_widths.size(), size_t(kDragTo - kDragFrom));
  EXPECT_EQ(over.drag_widths.front(), moving) << "the first drag frame is at the moving scale";
  for (size_t i = 1; i < over.drag_widths.size(); ++i)
    EXPECT_LE(over.drag_widths[i], over.drag_widths[i - 1]) << "drag frame " << i;
  EXPECT_EQ(over.drag_widths.back(), floor) << "0.9^7 of 0.5 is below the floor";
  EXPECT_EQ(over.release_width, floor) << "the release is shown at the drag's scale";
  EXPECT_TRUE(over.release_preview) << "with the drag's coarse light";
  EXPECT_EQ(over.full_width, kW) << "then at full resolution";
  EXPECT_FALSE(over.full_preview) << "with the light swept in full";
  // Every frame meets a budget of an hour: the scale never goes past the moving scale.
  const DragRun under = runDrag(3.6e6, "cb_light_drag_under");
  ASSERT_FALSE(under.drag_widths.empty());
  for (int w : under.drag_widths) EXPECT_EQ(w, moving);
  EXPECT_EQ(under.full_width, kW);
}

TEST(LightDrag, TheScalePolicyStepsWithinItsBounds) {
  PaintLoopOptions o;
  o.moving_scale = 0.5f;
  o.min_light_drag_scale = 0.25f;
  o.light_drag_frame_ms = 50.0;
  EXPECT_FLOAT_EQ(nextLightDragScale(0.5f, 80.0, o), 0.45f);   // over: a tenth less
  EXPECT_FLOAT_EQ(nextLightDragScale(0.26f, 80.0, o), 0.25f);  // not below the floor
  EXPECT_FLOAT_EQ(nextLightDragScale(0.4f, 40.0, o), 0.4f);    // within 70-100 %: kept
  EXPECT_FLOAT_EQ(nextLightDragScale(0.4f, 10.0, o), 0.42f);   // under 70 %: 5 % more
  EXPECT_FLOAT_EQ(nextLightDragScale(0.49f, 10.0, o), 0.5f);   // not past the moving scale
  EXPECT_FLOAT_EQ(quantisedScale(0.33f, 0.25f), 0.35f);
  EXPECT_FLOAT_EQ(quantisedScale(0.2f, 0.25f), 0.25f);
}

// A drag turning the view, drawn each way (MovingFrames): how many of its frames were
// reprojected or reduced, the size of the last cast once at rest again, and the view then.
struct CameraDragRun {
  long reprojected = 0, reduced = 0;
  int rest_width = 0, rest_height = 0;
  Camera before, camera;
};

CameraDragRun runCameraDrag(MovingFrames way, const std::string& name, bool at_detail = false) {
  CameraDragRun run;
  CumulusPainter fixture(name);
  std::string error;
  EXPECT_TRUE(fixture.open(&error)) << error;
  if (!fixture.painter.display) return run;
  const VolumeRenderer& renderer = fixture.painter.renderer;
  const PaintSession& session = *fixture.painter.session;
  PaintLoopOptions options = fixture.options();
  options.moving_frames = way;
  options.cast_at_volume_detail = at_detail;
  const PaintLoopSummary summary = runScriptedDrag(
      fixture, options, '1', 0.3f, 0.04f, 0.5f, [&](int frame, std::atomic<bool>& stop) {
        if (frame == kDragFrom) run.before = session.camera();
        if (frame == kDragTo + 6) {
          run.rest_width = renderer.lastStats().width;
          run.rest_height = renderer.lastStats().height;
          run.camera = session.camera();
          stop = true;
        }
      });
  run.reprojected = summary.reprojected_moving_frames;
  run.reduced = summary.reduced_moving_frames;
  return run;
}

TEST(CameraDrag, ItsFramesAreTheMovingFramesAndItsRestTheFullCast) {
  const CameraDragRun reduced = runCameraDrag(MovingFrames::kReduced, "cb_camera_drag_reduced");
  const CameraDragRun reprojected =
      runCameraDrag(MovingFrames::kReprojected, "cb_camera_drag_reprojected");
  // Each drag frame that turned the view (the press's own frame does not) is a moving frame.
  EXPECT_GE(reduced.reduced, kDragTo - kDragFrom - 2);
  EXPECT_EQ(reduced.reprojected, 0);
  EXPECT_GE(reprojected.reprojected, kDragTo - kDragFrom - 2);
  EXPECT_EQ(reprojected.reduced, 0);
  // At rest the view is cast whole at full resolution (the drag frames' casts were half as wide:
  // the moving scale ½, or one pixel in 2×2 reprojected).
  for (const CameraDragRun* run : {&reduced, &reprojected}) {
    EXPECT_GT(glm::length(run->camera.eye - run->before.eye), 0.05f) << "the drag turned the view";
    EXPECT_EQ(run->rest_width, kW);
    EXPECT_EQ(run->rest_height, kH);
  }
  // With the painter's default the rest frame is cast at the volume's detail: the 64³ cumulus's
  // voxels cover ~3 pixels here, so half the rays per axis (app/render/volume_detail.h).
  const CameraDragRun detail = runCameraDrag(MovingFrames::kReduced, "cb_camera_drag_detail",
                                             PaintLoopOptions{}.cast_at_volume_detail);
  EXPECT_EQ(detail.rest_width, kW / 2);
  EXPECT_EQ(detail.rest_height, kH / 2);
}

}  // namespace
}  // namespace cb
