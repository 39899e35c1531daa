// The interactive frame loop of `cloudbrush paint` on a display (KMS or X11): the scene (a volume
// and its light) seen by a slowly orbiting camera, drawn at reduced resolution while the camera
// moves and refined to full resolution when it stops (thesis §1.5: 256³ at 1280×768 at
// 20–30 fps was the interactive target). Esc, q or closing the window ends it; Space pauses the
// orbit. The pen will be routed into this loop later (an input router per mode); keep it small.
#pragma once

#include <atomic>
#include <string>

#include "app/render/gl/display.h"
#include "app/render/volume_renderer.h"
#include "app/scene/camera.h"
#include "app/scene/light.h"
#include "app/volume/volume.h"

namespace cb {

struct PaintLoopOptions {
  float orbit_degrees_per_second = 6.0f;  // a slow turn: one revolution per minute
  // Resolution scale while moving; adapted each frame towards target_frame_ms within
  // [min_moving_scale, 1].
  float moving_scale = 0.5f;
  float min_moving_scale = 0.2f;
  double target_frame_ms = 50.0;  // 20 fps
  long max_frames = 0;            // stop after this many presented frames (0: until quit)
  bool print_stats = false;       // ray-sample statistics of the last full-resolution frame
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
};

class PaintLoop {
 public:
  PaintLoop(Display& display, VolumeRenderer& renderer, const Volume& volume, const Light& light,
            const PaintLoopOptions& options);
  // Runs until a quit request, the frame limit or `*stop` becomes true (signal handlers set it).
  // False with a message if presenting fails.
  bool run(const std::atomic<bool>* stop, PaintLoopSummary* summary, std::string* error);

 private:
  // Applies the display's events; returns the quit reason or "".
  std::string handleEvents();

  Display& display_;
  VolumeRenderer& renderer_;
  const Volume& volume_;
  Light light_;
  PaintLoopOptions options_;
  bool orbiting_ = true;
  bool refined_ = false;  // the still image has been drawn at full resolution
  float orbit_degrees_ = 0.0f;
};

}  // namespace cb
