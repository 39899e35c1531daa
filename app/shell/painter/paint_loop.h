// The interactive frame loop of `cloudbrush paint` on a display (KMS or X11): the scene (a volume
// and its light) seen by a slowly orbiting camera, drawn at reduced resolution while the camera
// moves and refined to full resolution when it stops (thesis §1.5: 256³ at 1280×768 at
// 20–30 fps was the interactive target). Esc, q or closing the window ends it; Space pauses the
// orbit.
//
// With a pen attached (attachPen) the loop paints (thesis §3.3, §3.4): a pen in proximity stops
// the orbit, the still scene is rendered once into a cached target, and each frame only the live
// footprint (its changed rectangles) and the cursor are composited over it (FootprintOverlay),
// so a sample shows in the next frame. At tip-up the PaintSession maps the stroke into the
// volume; the renderer syncs the dirty box (upload, occupancy, light) and the lit scene is shown.
// A missing tablet is a state shown on stderr, never an exit: the orbit goes on.
//
// Modes, keys and the pen menu: see paint_screen.h.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "app/render/footprint_overlay.h"
#include "app/render/gl/display.h"
#include "app/render/hud_overlay.h"
#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"
#include "app/scene/camera.h"
#include "app/scene/light.h"
#include "app/shell/painter/moving_frames.h"
#include "app/volume/volume.h"
#include "drivers/core/pen_sample.h"

namespace cb {

class Clock;
class PaintSession;
class PenSource;
class Screen;

// What the frame just drawn showed, for tests (called before present, with the display's
// framebuffer bound and readable).
struct PaintFrameInfo {
  long frame = 0;
  bool painting_view = false;  // the cached still scene with the footprint overlay
  bool in_stroke = false;      // a stroke is being painted
  size_t texels_uploaded = 0;  // footprint texels uploaded for this frame
  // The ink was drawn again at the frame's end from samples latched then (late_ink): the box
  // re-blitted, in pixels (x0, y0, x1, y1, y down; 0 when nothing new came).
  bool late_ink = false;
  int late_box[4] = {0, 0, 0, 0};
  bool first_lit_after_lift = false;  // first frame showing the volume after a stroke was mapped
  double pen_up_to_lit_ms = 0.0;      // for that frame: lift sample received -> this frame drawn
  // The same from the lift sample's own timestamp (the kernel's; a replayed pen's restamped
  // time), including the journal's stroke-end sync; 0 when the sample's clock is not this one.
  double lift_sample_to_lit_ms = 0.0;
  double mapping_ms = 0.0;    // of which: the stroke mapper (StrokeMapper::map)
  double sync_ms = 0.0;       // renderer sync: occupancy, light, pack, upload
  double render_ms = 0.0;     // ray casting the scene (to glFinish; also when refined)
  double composite_ms = 0.0;  // the scene to the display (a blit on the lit frame)
  // The frame after the first lit one re-renders the scene at full resolution.
  bool refined_after_lift = false;
  double pen_up_to_refined_ms = 0.0;
  double lift_sample_to_refined_ms = 0.0;  // from the lift sample's timestamp, as above
  // The scene render of this frame (lit or refined): pixels ray cast (RenderStats::pixels_cast,
  // of the image at render_scale) and that scale; 0 when the scene was not re-rendered.
  long long rendered_pixels = 0;
  float render_scale = 0.0f;
};

struct PaintLoopOptions {
  // Ray casting settings from config/render.toml (scale and statistics are set per frame).
  RenderOptions render;
  float orbit_degrees_per_second = 6.0f;  // a slow turn: one revolution per minute
  // Resolution scale while moving; adapted each frame towards target_frame_ms within
  // [min_moving_scale, 1].
  float moving_scale = 0.5f;
  float min_moving_scale = 0.5f;           // never below half resolution
  double target_frame_ms = 1000.0 / 30.0;  // 30 fps
  // While the view moves (orbit, a drag turning the view, morph, wind): the reduced scale, full
  // resolution by temporal reprojection (one pixel in reprojectionFactor² cast a frame; ink,
  // sketch and sizes f does not divide keep the reduced scale), or whichever of the two keeps
  // to target_frame_ms or is the faster, measured (moving_frames.h; the default).
  MovingFrames moving_frames = MovingFrames::kFaster;
  // Frames cast at the volume's detail where that looks the same (volume_detail.h: the thesis and
  // physical styles; at rest at most half the rays per axis fewer than a ray per pixel, moving no
  // finer than the voxels need, down to 3/20); false casts a ray per pixel at rest and the
  // moving scale while moving (the bench's baselines).
  bool cast_at_volume_detail = true;
  // While the light ball is dragged the light is swept at 1/light_drag_divisor per axis into a
  // small texture the ray caster reads instead of the pool's light (reduced_light_sweep.h: the
  // thesis's 128³ preview for 256³), and in full at release; 1 sweeps the light volume in full
  // and re-packs the pool every drag frame (the bench's baseline).
  int light_drag_divisor = 2;
  // While a morph or the wind plays, the light of each frame is swept the same way, 1/divisor
  // per axis into that texture, and what the frames changed is swept in full when it stops
  // (VolumeRenderer's LightPreviewOf::kEveryChange); 1 sweeps every frame's change in full (the
  // bench's baseline).
  int animation_light_divisor = 2;
  // While the light ball is dragged the scene is cast at a scale of its own, adapted after each
  // drag frame towards light_drag_frame_ms (15 fps) within [min_light_drag_scale,
  // moving_scale], and kept for the next drag: the camera holds still, so the shading, not the
  // outline, is what a drag frame shows, and it stays fluid where the cloud fills the screen.
  double light_drag_frame_ms = 1000.0 / 15.0;
  float min_light_drag_scale = 0.25f;
  // After a stroke (or erase, undo) only the pixels whose rays cross what changed are
  // re-rendered (changed_region.h); false re-renders the whole frame (the bench's baseline).
  bool region_rerender = true;
  // After a lift the change is first shown at moving_scale, then refined, unless the last
  // full-resolution frames say it can be cast at full resolution within this long of the lift
  // (pen-up → first lit frame ≤ 100 ms); then it is shown so at once.
  double lift_budget_ms = 100.0;
  // The ink first: the live footprint and cursor are drawn from pen samples taken as late as
  // possible (after the scene's work, FrameContext::latch_pen), and a refinement to full
  // resolution waits while a stroke is drawn (it is cast after the lift). False: the loop
  // before (the bench's baseline).
  bool ink_first = true;
  // With ink_first: the ink drawn last. The frame (scene, ink, heads-up items, UI) is made
  // first; then the samples that came meanwhile are latched and only the pixels their ink and
  // the cursor changed are composited again, with the heads-up items and the UI drawn over them
  // again there, so a sample waits for its own ink, not for a whole frame. The frame is the one
  // the whole path would draw from the same samples. False: the ink latched once, before the
  // composite.
  bool late_ink = true;
  long max_frames = 0;                // stop after this many presented frames (0: until quit)
  double max_seconds = 0.0;           // stop after this long (0: until quit)
  bool print_stats = false;           // ray-sample statistics of the last full-resolution frame
  bool show_stats_overlay = false;    // start with the S overlay on
  bool show_circles_overlay = false;  // start with the C overlay on
  // Keys pressed before the first frame, as if typed (scripted runs and tests: `--keys`).
  std::vector<DisplayEvent> initial_keys;
  // Painting: where calibration profiles are looked up (calibration/profile_store.h).
  std::string config_dir, state_dir;
  // Where Save (Ctrl+S, the menu's Save) writes clouds and Open and the morph look for them;
  // empty: state_dir. A study session sets its session folder's saved/, so a participant's
  // clouds stay with their session (withdrawn and exported with it) and no participant opens
  // another's.
  std::string save_dir;
  // The left part of the width (a fraction) in which the answer to an action (a save's toast)
  // and the first screen's hint are centred: a study's panel covers the rest.
  float message_area = 1.0f;
  // The height (pixels) along the bottom of a width x height screen that the host draws over
  // (a study's foot line): the first screen's hint keeps above it. Null: nothing (the plain
  // painter, the kiosk).
  std::function<float(int width, int height)> message_bottom;
  // Morph (F): the saved cloud to morph into (`--morph-to`); empty: the newest saved cloud of
  // the save folder (save_dir, else state_dir), else the bundled cumulus ("bundled:1", the cloud
  // that orbits at the start). Played over morph_seconds, then held until applied (A) or left (X).
  std::string morph_target;
  double morph_seconds = 5.0;
  std::function<void(const PaintFrameInfo&)> on_frame;  // tests: after drawing, before present
  std::function<void()> on_first_connection;            // the pen connected for the first time
  std::function<void(bool presented)> each_iteration;   // every loop iteration (kiosk watchdog)
  // Exhibition kiosk: visitor mode keeps quit keys and operator commands away
  // (only painting, erasing, camera, undo and start again). Idle reset, attract loop, operator
  // panel and gallery are the kiosk screen's (kiosk_screen.h), which runs this screen.
  bool visitor_mode = false;
  std::function<void()> before_start_again;  // visitor mode: "start again" with a cloud painted
  const Clock* clock = nullptr;              // the frame loop's clock (frame_loop.h)
};

// What a run did, for the summary line and tests.
struct PaintLoopSummary {
  long frames = 0;
  double seconds = 0.0;
  double median_frame_ms = 0.0;    // present to present while orbiting
  double median_present_ms = 0.0;  // inside present(): swap (+ page flip wait on KMS)
  double final_moving_scale = 0.0;
  // Moving frames (orbit, a drag turning the view, morph, wind) drawn each way (moving_frames.h).
  long reprojected_moving_frames = 0, reduced_moving_frames = 0;
  long refined_frames = 0;  // full-resolution frames drawn after the camera stopped
  std::string quit_reason;  // "Esc", "window closed", "frame limit", "signal"
  long pen_samples = 0;
  long painting_frames = 0;               // frames presented while a stroke was being drawn
  double median_painting_frame_ms = 0.0;  // present to present during strokes
  long strokes_mapped = 0;
  std::vector<double> pen_up_to_lit_ms;  // per mapped stroke: lift received -> lit frame drawn
  std::vector<double> mapping_ms, sync_ms, render_ms;  // per mapped stroke, parts of the above
  std::vector<double> pen_up_to_refined_ms;  // per mapped stroke: lift -> full-resolution frame
  // The same two from the lift sample's timestamp (with the stroke-end journal sync); empty
  // when the pen's clock is not the loop's (a replay fed as fast as polled).
  std::vector<double> lift_sample_to_lit_ms, lift_sample_to_refined_ms;
  double median_pen_up_to_lit_ms() const;
};

// The painter's moving-resolution policy (orbit): after a moving frame that took frame_ms, the
// next scale shrinks by 10% when over target_frame_ms and grows by 5% below 70% of it, within
// [min_moving_scale, 1].
inline float nextAdaptedScale(float scale, double frame_ms, double target_ms, float lo, float hi) {
  if (frame_ms > target_ms) return std::max(lo, scale * 0.9f);
  if (frame_ms < 0.7 * target_ms) return std::min(hi, scale * 1.05f);
  return scale;
}
inline float nextMovingScale(float scale, double frame_ms, const PaintLoopOptions& options) {
  return nextAdaptedScale(scale, frame_ms, options.target_frame_ms, options.min_moving_scale, 1.0f);
}
// The light drag's (PaintLoopOptions::light_drag_frame_ms): the same steps, within
// [min_light_drag_scale, moving_scale].
inline float nextLightDragScale(float scale, double frame_ms, const PaintLoopOptions& options) {
  const float hi = std::max(options.moving_scale, options.min_light_drag_scale);
  return nextAdaptedScale(scale, frame_ms, options.light_drag_frame_ms,
                          options.min_light_drag_scale, hi);
}
// The scale a moving frame is rendered at: quantised to 1/20 so the renderer's reduced-size
// target is not reallocated every frame, never below `lo`.
inline float quantisedScale(float scale, float lo) {
  return std::max(lo, std::round(scale * 20.0f) / 20.0f);
}
inline float orbitRenderScale(float scale, const PaintLoopOptions& options) {
  return quantisedScale(scale, options.min_moving_scale);
}

class PaintScreen;

// `cloudbrush paint` on a display: the frame loop (frame_loop.h) running the painter's screen
// (paint_screen.h). Kept as one object for the command and its tests.
class PaintLoop {
 public:
  PaintLoop(Display& display, VolumeRenderer& renderer, const Volume& volume, const Light& light,
            const PaintLoopOptions& options);
  ~PaintLoop();
  // Runs until a quit request, the frame limit or `*stop` becomes true (signal handlers set it).
  // False with a message if presenting fails.
  // `front`, when given, is run instead of the paint screen and routes to it (the kiosk).
  bool run(const std::atomic<bool>* stop, PaintLoopSummary* summary, std::string* error,
           Screen* front = nullptr);

  // Routes `pen` into `session` (neither owned). The loop's own volume is shown until the pen
  // first connects, the session's volume from then on.
  void attachPen(PenSource* pen, PaintSession* session);
  PaintScreen& screen() { return *screen_; }
  // Every command the loop routed, by name, in order (tests).
  const std::vector<std::string>& routedCommands() const { return routed_; }

 private:
  Display& display_;
  std::unique_ptr<PaintScreen> screen_;
  PenSource* pen_ = nullptr;
  PaintLoopOptions options_;
  std::vector<std::string> routed_;
};

}  // namespace cb
