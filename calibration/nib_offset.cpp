#include "calibration/nib_offset.h"

#include <algorithm>
#include <cmath>

namespace cb {

void NibOffsetDetector::observe(const PenSample& s, bool has_distance) {
  if (!s.in_proximity || !std::isfinite(s.pressure)) return;
  const bool hovering_high =
      has_distance ? (!s.tipDown() && s.distance >= params_.hover_high_distance) : !s.tipDown();
  if (!hovering_high) return;
  const float p = std::clamp(s.pressure, 0.0f, 1.0f);
  window_min_ = window_has_sample_ ? std::min(window_min_, p) : p;
  window_has_sample_ = true;
  if (window_min_ <= params_.max_offset) {
    offset_ = window_min_;
    rejected_ = false;
  } else {
    rejected_ = true;
  }
}

float NibOffsetDetector::correct(float pressure) const {
  if (!std::isfinite(pressure)) return 0.0f;
  if (offset_ >= 1.0f) return 0.0f;
  return std::clamp((pressure - offset_) / (1.0f - offset_), 0.0f, 1.0f);
}

}  // namespace cb
