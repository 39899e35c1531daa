// Worn-nib pressure offset. An old nib (or a sticky spring) reports some pressure even in the
// air, which would paint on its own. At every proximity-in the detector starts a new window and
// takes the minimum pressure seen while the pen hovers high (distance at or above
// `hover_high_distance`, or simply not touching on pens without a distance axis); that minimum
// is the offset subtracted from every pressure (as libinput's tablet pressure offset does).
// An implausibly large minimum (above `max_offset`) is not a worn nib but a pen pressed at
// proximity-in; it is rejected and the previous offset kept.
//
//   p' = clamp((p - offset) / (1 - offset), 0, 1)
#pragma once

#include "drivers/core/pen_sample.h"

namespace cb {

struct NibOffsetParams {
  float hover_high_distance = 0.5f;  // normalised distance that counts as hovering high
  float max_offset = 0.2f;           // larger minima are rejected
};

class NibOffsetDetector {
 public:
  NibOffsetDetector() = default;
  explicit NibOffsetDetector(const NibOffsetParams& p) : params_(p) {}
  void setParams(const NibOffsetParams& p) { params_ = p; }

  // The pen came into proximity: start a new detection window (the offset found so far stays
  // in force until the new window sees a hovering sample).
  void proximityIn() { window_has_sample_ = false; }
  // Observes one in-proximity sample. `has_distance`: the device reports a hover distance.
  void observe(const PenSample& s, bool has_distance);

  float offset() const { return offset_; }
  // True when the last window's minimum exceeded max_offset and was ignored.
  bool rejected() const { return rejected_; }
  // Pressure with the offset removed, rescaled to 0..1.
  float correct(float pressure) const;

 private:
  NibOffsetParams params_;
  bool window_has_sample_ = false;
  float window_min_ = 0.0f;
  float offset_ = 0.0f;
  bool rejected_ = false;
};

}  // namespace cb
