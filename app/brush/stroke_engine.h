// The stroke lifecycle (thesis §3.4, §5.3.1 Fig. 5.6): tip-down starts a stroke with a fresh,
// never-cleared footprint; each pen sample is repaired or dropped (brush_input.h), recorded in
// the path and handed to the brush; tip-up ends the stroke and yields a StrokeResult for the
// mapping. The engine never decides contact itself: it is driven explicitly
// (beginStroke/addSample/endStroke) or by the calibration's hysteresis (feedCalibrated), the one
// decision the pen events (app/shell/pen_events.h) are derived from too.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>

#include "app/brush/brush.h"
#include "app/brush/brush_input.h"
#include "calibration/mapped_sample.h"

namespace cb {

class StrokeEngine {
 public:
  StrokeEngine(const BrushConfig& config, int footprint_width, int footprint_height);

  // Takes effect at the next tip-down.
  void selectBrush(BrushKind kind) { selected_ = kind; }
  // The brush size (brush_config.h stroke.size): the footprint is the constructor's
  // width × height divided by `size` (at least 1 × 1), and positions are scaled to it, so the
  // brush's mark covers `size` times more of the screen. Takes effect at the next tip-down.
  void setBrushSize(float size);
  float brushSize() const { return size_; }
  // The footprint the next stroke gets (the current stroke's while one is painted).
  int footprintWidth() const { return in_stroke_ ? footprint_.width : width_; }
  int footprintHeight() const { return in_stroke_ ? footprint_.height : height_; }
  BrushKind selectedBrush() const { return selected_; }
  void setPaintView(const PaintView& view, const Canvas& canvas) {
    view_ = view;
    canvas_ = canvas;
  }
  void setNextStrokeIndex(uint32_t index) { next_index_ = index; }
  uint32_t nextStrokeIndex() const { return next_index_; }

  // Explicit contact. beginStroke returns an empty rect and stays up if the sample is dropped.
  FootprintRect beginStroke(const BrushInput& input);
  FootprintRect addSample(const BrushInput& input);
  StrokeResult endStroke();
  // Ends a stroke in progress as if the pen lifted and queues it for takeFinishedStroke().
  void finishStroke() {
    if (in_stroke_) finished_.push_back(endStroke());
  }

  bool takeFinishedStroke(StrokeResult* out);

  // Calibrated contact (calibration/'s hysteresis): contact_began starts a stroke, contact
  // continues it, contact_ended ends it (queued for takeFinishedStroke). The raw PenSamples of
  // the stroke are kept in StrokeResult::raw_path.
  FootprintRect feedCalibrated(const MappedSample& sample);

  // Readies the next stroke's zeroed footprint and noise pattern while the pen is up, so tip-down
  // costs no allocation (≈1 ms at 1280×720). Done at construction and on hover samples through
  // feedCalibrated(); call it yourself when driving contact explicitly. Idempotent.
  void prepareNextStroke();

  bool inStroke() const { return in_stroke_; }
  // The live footprint of the current stroke (empty between strokes).
  const Footprint& footprint() const { return footprint_; }
  const InputStats& inputStats() const { return stats_; }
  Brush& brush(BrushKind kind);

 private:
  StrokePoint toPoint(const BrushInput& in) const;

  BrushConfig config_;
  int base_width_, base_height_;  // the footprint at size 1
  int width_, height_;            // at size_
  float size_ = 1.0f;
  glm::vec2 input_scale_;  // footprint pixels per screen pixel at size_
  BrushKind selected_;
  std::unique_ptr<Brush> brushes_[3];
  Brush* active_ = nullptr;
  PaintView view_{Camera::reference()};
  Canvas canvas_;
  Footprint footprint_;
  Footprint spare_;  // the next stroke's zeroed footprint, allocated at tip-up, not tip-down
  std::vector<StrokePoint> path_;
  std::vector<PenSample> raw_path_;
  bool in_stroke_ = false;
  uint32_t next_index_ = 0, current_index_ = 0;
  InputHistory history_;
  InputStats stats_;
  std::deque<StrokeResult> finished_;
};

}  // namespace cb
