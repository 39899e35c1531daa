// The painter's animations: a morph from the cloud into a saved cloud over a set
// time, or wind blowing it, played on a copy of the session's cloud for display. The session's
// cloud is not touched while it plays: "apply" commits the frame shown as one history step and
// one journal record (PaintSession::commitAnimation with ui::ApplyMorph / ui::ApplyWind, which
// replay recomputes), and leaving without applying drops the copy, so the cloud shows as it was.
//
// Both work on the tool's window of the sky (tool_window.h; the whole cloud in a one-box sky):
// the window is cropped out when the animation starts, each frame is made on the window's copy
// and pasted into the display copy of the whole sky (what the renderer is given), so a frame
// costs what the window holds, and only the bricks that changed are uploaded. The wind's next
// frame is made on another thread while the renderer draws this one (its steps do not depend on
// what is shown), so a wind frame costs the longer of the two, not their sum.
// The display copy is at half the resolution when the home box is 128³ or more (halfResolution:
// an eighth of the voxels to move, upload and light each frame). The morph is planned once from
// the full-resolution windows, and both they and the copy are carried along its paths when the
// morph starts (so apply only frames the full clouds: no re-planning); the wind's velocity grid
// and flow map are the same at any resolution. Apply then computes the window's frame shown at
// full resolution — the morph's frame at the same t from the same plan, the wind's flow map
// resampling the full window once — which is exactly what replay computes from the record, and
// commits that.
// A change to the session's cloud while an animation is shown (a stroke, undo, open…) leaves
// the animation first: the copy no longer starts from the cloud.
#pragma once

#include <future>
#include <memory>
#include <optional>
#include <string>

#include "app/session/paint_session.h"
#include "app/tools/cloud_animation.h"
#include "app/tools/cloud_morph.h"

namespace cb {

class AnimationPreview {
 public:
  enum class Kind { kNone, kMorph, kWind };

  // Plans a morph from the session's cloud into `target_source` (loadMorphTarget) played over
  // `seconds`. False with *error (nothing started) for an empty cloud, a missing or unfitting
  // target.
  bool startMorph(const PaintSession& session, const std::string& target_source, double seconds,
                  std::string* error);
  // Starts the wind (towards the current direction) on a copy of the session's cloud, or
  // pauses / resumes it when it is already shown. False with *error (nothing started) when the
  // cloud is empty.
  bool toggleWind(const PaintSession& session, std::string* error);
  // The next of eight compass directions; a running wind turns from the next step.
  void nextWindDirection();
  // Advances a playing animation by a frame: the morph by `seconds` of its time, the wind by
  // one step. True when the shown cloud changed.
  bool advance(double seconds);
  // advance() by the time since the previous call (a frame's monotonic time; the first call
  // after a start counts from then, a pause longer than 0.25 s counts as 0.25 s).
  bool advanceTo(int64_t now_ns);
  // The record that recomputes the frame shown (valid while active()).
  UiChange change() const;
  // Commits the frame shown (at full resolution) to the session and ends the animation.
  bool apply(PaintSession* session, int64_t t_ns, std::string* error);
  // The full-resolution frame of what is shown on the window (what apply commits).
  WindowFrame fullFrame(const PaintSession& session) const;
  // Whether the display copy is at half resolution (set before starting; default: when the home
  // box is 128³ or larger).
  void setHalfResolution(std::optional<bool> half) { half_ = half; }
  bool atHalfResolution() const { return shown_ && shown_->dims() != base_dims_; }
  // Ends the animation without applying.
  void leave();
  // Whether the session's cloud changed since the animation started from it.
  bool stale(const PaintSession& session) const;

  Kind kind() const { return kind_; }
  bool active() const { return kind_ != Kind::kNone; }
  bool playing() const { return active() && playing_; }
  // The display copy of the whole sky (at half resolution or full).
  const Volume& shown() const { return *shown_; }
  // The window the animation works on (in the session's voxels).
  const ToolWindow& window() const { return window_; }
  float morphT() const { return t_; }
  int windSteps() const { return wind_ ? wind_->run().steps() : 0; }
  const char* windDirectionName() const;
  // What the status line says about the animation ("" when none).
  std::string status() const;

 private:
  Kind kind_ = Kind::kNone;
  bool playing_ = false;
  std::unique_ptr<Volume> shown_;  // the display copy of the sky
  std::unique_ptr<Volume> frame_;  // the window's display frame, pasted into shown_
  std::unique_ptr<Volume> start_;  // the wind's starting window (display copy)
  ToolWindow window_;
  glm::ivec3 display_at_{0};  // where frame_ goes in shown_
  uint64_t base_instance_ = 0, base_generation_ = 0;
  int64_t last_advance_ns_ = -1;
  std::optional<bool> half_;
  glm::ivec3 base_dims_{0};
  bool useHalf(const Volume& cloud, const ToolWindow& window) const;
  // Starts showing: shown_ the sky's display copy, frame_ (and for the wind start_) its window.
  void startDisplay(const Volume& cloud, const ToolWindow& window);
  // frame_'s voxels in `region` (frame_'s voxels) into shown_.
  void paste(const VoxelBox& region);
  // Morph
  std::unique_ptr<CloudMorph> morph_;
  std::unique_ptr<CloudMorph> morph_full_;  // the full-resolution clouds along the same plan
  std::string target_;
  uint64_t target_checksum_ = 0;
  double seconds_ = 5.0;
  float t_ = 0.0f;
  VoxelBox written_;
  // Wind
  int direction_ = 0;                    // 0 east, 1 north-east, … (x is east, −z is north)
  std::unique_ptr<WindAnimation> wind_;  // the wind as shown: its steps made frame_
  // The wind's next frame is made on another thread while this one is drawn: a copy of the wind
  // (made on that thread) stepped once, carrying start_ into the spare frame (the frame shown
  // before this one, whose content spare_written_ bounds). The next advance takes it; a turn of the
  // wind or leaving drops it (a turn applies from the next step), a pause keeps it.
  struct WindStep {
    std::unique_ptr<WindAnimation> wind;
    std::unique_ptr<Volume> frame;
    VoxelBox written;
  };
  // `wind` copied into `storage` (its allocations reused), or into a new one when there is none.
  static std::unique_ptr<WindAnimation> copyOf(const WindAnimation& wind,
                                               std::unique_ptr<WindAnimation> storage);
  static WindStep stepWind(std::unique_ptr<WindAnimation> wind, const Volume& start,
                           std::unique_ptr<Volume> frame, const VoxelBox& previous);
  void startWindAhead();
  void dropWindAhead();
  std::unique_ptr<Volume> spare_frame_;
  VoxelBox spare_written_;
  std::unique_ptr<WindAnimation> spare_wind_;  // the wind before: storage for the next copy
  std::future<WindStep> wind_ahead_;           // last: it reads start_, so it is waited for first
};

}  // namespace cb
