// The kiosk's attract loop: while nobody paints, a recorded session journal is
// replayed at the pace it was painted (times `speed`; the strokes are mapped once, on a thread of
// their own: attract_replay.h, so no frame waits for a mapping), the camera
// slowly orbiting, with the invitation over it; when the journal has played, the finished cloud
// keeps orbiting for `hold_s`. Then, when the kiosk keeps a gallery, the cloud morphs
// (app/tools/cloud_morph.h, played as the painter plays it: AnimationPreview) into up to
// `gallery_morphs` visitors' clouds in turn — newest first, each loop going on from the last
// one shown — each over `morph_seconds` and held for `hold_s`; then the replay starts again on
// an empty sky. A gallery cloud that cannot be read or does not fit the sky is skipped and
// named in problems(). Every timer reads
// the injected Clock. The kiosk screen (kiosk_screen.h) hands control to the visitor on the
// first pen proximity, mouse or key, and restarts this loop after the idle reset.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "app/brush/brush_config.h"
#include "app/mapping/mapping_config.h"
#include "app/render/volume_renderer.h"
#include "app/scene/light.h"
#include "app/session/paint_session.h"
#include "app/shell/kiosk/attract_replay.h"
#include "app/shell/painter/animation_preview.h"
#include "app/shell/screen.h"
#include "app/shell/ui_overlay.h"
#include "drivers/core/clock.h"
#include "drivers/core/journal.h"

namespace cb {

struct AttractOptions {
  float orbit_degrees_per_second = 6.0f;
  double hold_s = 10.0;  // the finished cloud orbits this long before the replay restarts
  double speed = 1.0;    // journal seconds per clock second
  int grid = 0;          // volume resolution of the replay (0: the journal's)
  BrushConfig brush;
  MappingConfig mapping;
  RenderOptions render;          // scale: the orbit's resolution scale
  Light light;                   // until the journal sets its own
  std::string invitation, hint;  // big and small lines in the middle of the screen
  std::string notice;            // a small line at the bottom (what is kept, for how long)
  std::string gallery_dir;       // the kiosk's gallery (app/kiosk/gallery_store.h); "": none
  int gallery_morphs = 2;        // gallery clouds morphed into per loop
  double morph_seconds = 6.0;    // each morph's length
  // A frame that took longer than slice_ms (a slow box, an emulated CPU) is drawn in horizontal
  // bands of about that long each (at most max_slices); between them, and while each band is
  // being drawn, the screen asks whether pen input waits (FrameContext::input_waiting) and, if
  // so, gives the frame up: the loop takes the pen at once instead of after the frame (issue
  // 11: the tablet's first sample on the screen within 1 s of plugging it in). The bands
  // together are the whole frame, pixel for pixel. 0: always whole frames.
  double slice_ms = 60.0;
  int max_slices = 16;
};

class AttractScreen : public Screen {
 public:
  // `journal`: the records to replay (may be empty: the empty sky orbits). `ui` draws the text
  // (may be null: no text); not owned.
  AttractScreen(VolumeRenderer& renderer, const Clock& clock, std::vector<JournalRecord> journal,
                AttractOptions options, UiOverlay* ui);
  ~AttractScreen() override;

  const char* name() const override { return "attract"; }
  void onCommand(Command, int64_t) override {}
  std::string update(const FrameContext& frame) override;
  bool draw(FrameContext& frame, std::string* error) override;
  // Keeps the orbit fluid: the resolution scale shrinks when a frame is over 50 ms (20 fps) and
  // grows back when there is room, within [0.2, 1] (as the painter's orbit does). The frame's
  // length also sets how many slices the next one is drawn in.
  void presented(const FrameContext& frame, double frame_ms) override;
  float scale() const { return options_.render.scale; }
  // The slices the next frame is drawn in (1: whole), and those of the last frame drawn that
  // were finished (all of them unless it was given up).
  int slices() const;
  int slicesFinished() const { return slices_finished_; }
  // When the slice in flight (or the last one drawn) began, in monotonic nanoseconds: the
  // frame's start for the sync before the first band.
  int64_t sliceStartedNs() const { return slice_started_ns_; }
  long framesGivenUp() const { return frames_given_up_; }

  // Starts the replay from the beginning at the clock's time (an empty sky), at the resolution
  // scale the options gave.
  void restart();
  void setTexts(std::string invitation, std::string hint, std::string notice);

  // For tests and the health status.
  const Volume& volume() const { return morph_applied_ ? session_->volume() : *shown_.volume; }
  const Camera& shownCamera() const { return camera_; }
  // Records played by the clock (never past those the replay's worker has mapped: when it is
  // behind, the replay holds and goes on when it catches up).
  size_t recordsPlayed() const { return next_; }
  size_t recordCount() const { return replay_->recordCount(); }
  // Waits for the worker to map the whole journal (tests that drive the clock fast).
  void waitUntilPrepared() const { replay_->waitUntilFinished(); }
  long loopsCompleted() const { return loops_; }
  // The cloud shown: the replayed session's, or a morph's frame while one plays.
  const Volume& shownVolume() const;
  bool morphing() const { return morph_ && morph_->active(); }
  int morphsThisLoop() const { return morphs_; }
  long lastGalleryShown() const { return last_gallery_; }
  const std::vector<std::string>& problems() const { return problems_; }

 private:
  VolumeRenderer& renderer_;
  const Clock& clock_;
  AttractOptions options_;
  float start_scale_ = 1.0f;  // options.render.scale as given: where each loop starts
  UiOverlay* ui_;
  PaintSessionSettings settings_;
  std::unique_ptr<AttractReplay> replay_;
  AttractKeyframe shown_;  // the replay's state at next_ records
  // The morphs' session: the replayed cloud, then each gallery cloud morphed into (null until
  // the first morph of a loop); after a morph is applied it is what is shown (morph_applied_).
  std::unique_ptr<PaintSession> session_;
  bool morph_applied_ = false;
  int64_t started_ns_ = 0;       // clock time the replay (re)started (moved on while it holds)
  int64_t last_update_ns_ = 0;   // clock time of the last update
  int64_t finished_ns_ = -1;     // clock time the last record played (-1: still playing)
  int64_t orbit_start_ns_ = -1;  // the orbit's time origin (kept across restarts)
  size_t next_ = 0;
  size_t problems_seen_ = 0;  // of the replay's problems, those already in problems_
  long loops_ = 0;
  Camera camera_;
  std::vector<std::string> problems_;
  // Frames drawn in slices (AttractOptions::slice_ms).
  // Waits for the GL work sent so far while watching for input; false: input waits (the frame
  // is to be given up).
  bool drawnUnlessInputWaits(FrameContext& frame);
  bool giveUp(FrameContext& frame, int slices);
  double last_frame_ms_ = 0.0;  // present to present, of the last frame shown
  int slices_finished_ = 0;
  int64_t slice_started_ns_ = 0;
  int given_up_in_a_row_ = 0;
  long frames_given_up_ = 0;
  // Morphs into gallery clouds after the replay.
  bool startNextMorph();
  std::unique_ptr<AnimationPreview> morph_;
  int morphs_ = 0;          // begun in this loop
  long last_gallery_ = -1;  // number of the gallery entry last morphed into (-1: none yet)
};

}  // namespace cb
