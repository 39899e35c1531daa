#include "app/brush/stroke_engine.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "app/brush/calibrated_input.h"

namespace cb {

StrokeEngine::StrokeEngine(const BrushConfig& config, int width, int height)
    : config_(config),
      base_width_(width),
      base_height_(height),
      width_(width),
      height_(height),
      input_scale_(config.stroke.footprint_scale),
      selected_(config.default_brush) {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument("StrokeEngine: footprint size must be positive, got " +
                                std::to_string(width) + "x" + std::to_string(height));
  prepareNextStroke();
}

void StrokeEngine::setBrushSize(float size) {
  size_ = size;
  if (size == 1.0f) {
    width_ = base_width_;  // exactly the footprint and positions before the size existed
    height_ = base_height_;
    input_scale_ = glm::vec2(config_.stroke.footprint_scale);
    return;
  }
  width_ = std::max(1, int(std::lround(double(base_width_) / double(size))));
  height_ = std::max(1, int(std::lround(double(base_height_) / double(size))));
  // Per axis, so the coarser footprint still spans exactly the screen the pen maps to.
  input_scale_ = config_.stroke.footprint_scale * glm::vec2(float(width_) / float(base_width_),
                                                            float(height_) / float(base_height_));
}

void StrokeEngine::prepareNextStroke() {
  if (spare_.width != width_ || spare_.height != height_) spare_ = Footprint(width_, height_);
  brush(selected_).prepareStroke(next_index_);
}

Brush& StrokeEngine::brush(BrushKind kind) {
  std::unique_ptr<Brush>& b = brushes_[int(kind)];
  if (!b) b = makeBrush(kind, config_);
  return *b;
}

StrokePoint StrokeEngine::toPoint(const BrushInput& in) const {
  return {in.footprint_px, in.pressure, in.tilt_x_deg, in.tilt_y_deg, in.t_ns};
}

FootprintRect StrokeEngine::beginStroke(const BrushInput& input) {
  if (in_stroke_) finished_.push_back(endStroke());  // a missed tip-up: keep the stroke
  BrushInput in = input;
  Brush& b = brush(selected_);
  history_ = {};
  if (!sanitizeBrushInput(&in, width_, height_, b.reachPx(), &history_, &stats_)) return {};
  active_ = &b;
  in_stroke_ = true;
  current_index_ = next_index_++;
  if (spare_.width == width_ && spare_.height == height_)
    footprint_ = std::move(spare_);
  else
    footprint_ = Footprint(width_, height_);
  spare_ = Footprint();
  path_.clear();
  raw_path_.clear();
  path_.push_back(toPoint(in));
  return active_->beginStroke(current_index_, path_.back(), &footprint_);
}

FootprintRect StrokeEngine::addSample(const BrushInput& input) {
  if (!in_stroke_) return beginStroke(input);
  BrushInput in = input;
  if (!sanitizeBrushInput(&in, width_, height_, active_->reachPx(), &history_, &stats_)) return {};
  path_.push_back(toPoint(in));
  return active_->continueStroke(path_.back(), &footprint_);
}

StrokeResult StrokeEngine::endStroke() {
  StrokeResult result;
  if (!in_stroke_) return result;
  active_->endStroke(&footprint_);
  in_stroke_ = false;
  result.stroke_index = current_index_;
  result.brush = active_->kind();
  result.footprint = std::move(footprint_);
  result.view = view_;
  result.canvas = canvas_;
  result.path = std::move(path_);
  result.raw_path = std::move(raw_path_);
  footprint_ = Footprint();
  path_.clear();
  raw_path_.clear();
  active_ = nullptr;
  return result;
}

FootprintRect StrokeEngine::feedCalibrated(const MappedSample& sample) {
  BrushInput in = brushInputFromCalibrated(sample, input_scale_);
  FootprintRect changed;
  if (sample.contact_began || (sample.contact && !in_stroke_))
    changed = beginStroke(in);
  else if (sample.contact)
    changed = addSample(in);
  else if (!in_stroke_ && !sample.contact_ended)
    prepareNextStroke();  // hovering: get the next stroke ready
  if (in_stroke_) raw_path_.push_back(sample.raw);
  if (sample.contact_ended && in_stroke_) finished_.push_back(endStroke());
  return changed;
}

bool StrokeEngine::takeFinishedStroke(StrokeResult* out) {
  if (finished_.empty()) return false;
  *out = std::move(finished_.front());
  finished_.pop_front();
  return true;
}

}  // namespace cb
