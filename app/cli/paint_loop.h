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
// Keys: S toggles the ray-sample statistics overlay (histogram bars, total/mean/max samples),
// C toggles the last stroke's circles (rings where they were grown), B cycles the brush
// 2d -> 3d -> skeleton and M the mapping hybrid <-> ray-marching (both journalled as UI records
// through PaintSession::applyUi, so a replay repeats them). While the pen is in range the
// screen region where the canvas slab meets the volume is outlined faintly: strokes outside it
// cannot land in the volume.
#pragma once

#include <atomic>
#include <chrono>
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
#include "app/volume/volume.h"
#include "drivers/core/pen_sample.h"

namespace cb {

class PaintSession;
class PenSource;

// What the frame just drawn showed, for tests (called before present, with the display's
// framebuffer bound and readable).
struct PaintFrameInfo {
  long frame = 0;
  bool painting_view = false;         // the cached still scene with the footprint overlay
  bool in_stroke = false;             // a stroke is being painted
  size_t texels_uploaded = 0;         // footprint texels uploaded for this frame
  bool first_lit_after_lift = false;  // first frame showing the volume after a stroke was mapped
  double pen_up_to_lit_ms = 0.0;      // for that frame: lift sample received -> this frame drawn
  double mapping_ms = 0.0;            // of which: the stroke mapper (StrokeMapper::map)
  double sync_ms = 0.0;               // renderer sync: occupancy, light, pack, upload
  double render_ms = 0.0;             // ray casting the scene (to glFinish)
  double composite_ms = 0.0;          // the scene to the display (a blit on the lit frame)
  // The frame after the first lit one re-renders the scene at full resolution.
  bool refined_after_lift = false;
  double pen_up_to_refined_ms = 0.0;
};

struct PaintLoopOptions {
  float orbit_degrees_per_second = 6.0f;  // a slow turn: one revolution per minute
  // Resolution scale while moving; adapted each frame towards target_frame_ms within
  // [min_moving_scale, 1].
  float moving_scale = 0.5f;
  float min_moving_scale = 0.2f;
  double target_frame_ms = 50.0;      // 20 fps
  long max_frames = 0;                // stop after this many presented frames (0: until quit)
  bool print_stats = false;           // ray-sample statistics of the last full-resolution frame
  bool show_stats_overlay = false;    // start with the S overlay on
  bool show_circles_overlay = false;  // start with the C overlay on
  // Keys pressed before the first frame, as if typed (scripted runs and tests: `--keys`).
  std::vector<DisplayEvent::Key> initial_keys;
  // Painting: where calibration profiles are looked up (calibration/profile_store.h).
  std::string config_dir, state_dir;
  std::function<void(const PaintFrameInfo&)> on_frame;  // tests: after drawing, before present
  std::function<void()> on_first_connection;            // the pen connected for the first time
};

// What a run did, for the summary line and tests.
struct PaintLoopSummary {
  long frames = 0;
  double seconds = 0.0;
  double median_frame_ms = 0.0;    // present to present while orbiting
  double median_present_ms = 0.0;  // inside present(): swap (+ page flip wait on KMS)
  double final_moving_scale = 0.0;
  long refined_frames = 0;  // full-resolution frames drawn after the camera stopped
  std::string quit_reason;  // "Esc", "window closed", "frame limit", "signal"
  long pen_samples = 0;
  long painting_frames = 0;               // frames presented while a stroke was being drawn
  double median_painting_frame_ms = 0.0;  // present to present during strokes
  long strokes_mapped = 0;
  std::vector<double> pen_up_to_lit_ms;  // per mapped stroke: lift received -> lit frame drawn
  std::vector<double> mapping_ms, sync_ms, render_ms;  // per mapped stroke, parts of the above
  std::vector<double> pen_up_to_refined_ms;  // per mapped stroke: lift -> full-resolution frame
  double median_pen_up_to_lit_ms() const;
};

class PaintLoop {
 public:
  PaintLoop(Display& display, VolumeRenderer& renderer, const Volume& volume, const Light& light,
            const PaintLoopOptions& options);
  // Runs until a quit request, the frame limit or `*stop` becomes true (signal handlers set it).
  // False with a message if presenting fails.
  bool run(const std::atomic<bool>* stop, PaintLoopSummary* summary, std::string* error);

  // Routes `pen` into `session` (neither owned). The loop's own volume is shown until the pen
  // first connects, the session's volume from then on.
  void attachPen(PenSource* pen, PaintSession* session);

 private:
  // Applies the display's events (and, the first time, options.initial_keys); returns the quit
  // reason or "".
  std::string handleEvents();
  // Polls the pen and feeds the session; updates the overlay, cursor and lift timing.
  void handlePen(PaintLoopSummary* summary);
  // The still painting view: cached scene (re-rendered when stale) + footprint + cursor.
  void drawPaintingView(PaintFrameInfo* info);
  bool paintingSetUp(std::string* error);
  // Draws the enabled HUD items (S, C, canvas region) over the display framebuffer.
  bool drawHud(std::string* error);
  // B and M: the next brush / mapping method, journalled through the session.
  void cycleBrush();
  void cycleMapping();

  Display& display_;
  VolumeRenderer& renderer_;
  const Volume& volume_;
  Light light_;
  PaintLoopOptions options_;
  bool orbiting_ = true;
  bool refined_ = false;  // the still image has been drawn at full resolution
  float orbit_degrees_ = 0.0f;

  PenSource* pen_ = nullptr;
  PaintSession* session_ = nullptr;
  int last_connection_ = -1;
  bool pen_connected_once_ = false;
  const Volume& shownVolume() const;
  uint64_t tool_serial_ = 0;
  FootprintOverlay overlay_;
  RenderTarget scene_;  // the still scene, rendered once per camera or volume change
  bool overlay_ready_ = false;
  bool scene_stale_ = true;
  bool lit_pending_ = false;     // a stroke was mapped; its lit frame is not drawn yet
  bool refine_pending_ = false;  // the scene was last drawn at reduced resolution
  std::chrono::steady_clock::time_point lift_time_;
  double lift_mapping_ms_ = 0.0;
  size_t texels_this_frame_ = 0;
  OverlayCursor cursor_;
  std::vector<PenSample> samples_;
  HudOverlay hud_;
  bool show_stats_ = false, show_circles_ = false;
  bool initial_keys_pressed_ = false;
};

}  // namespace cb
