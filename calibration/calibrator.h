// The calibration pipeline: PenSample in, MappedSample out, one call per sample.
//
//   proximity-in  -> new nib-offset window; filters reset
//   pressure      -> nib offset removed -> contact hysteresis (tip-down resets the filters)
//                 -> participant range -> pressure curve
//   position (mm) -> 1€ filter -> area mapping + N-point correction -> screen px
//                 -> predicted preview (extrapolated from the filtered velocity)
//   tilt (deg)    -> zero offset -> 1€ filter -> azimuth / altitude
//
// Why each stage matters (thesis §5.1.2): of the five controls of a Chinese brush, pressure
// (stroke thickness), speed (ink dispersion) and tilt (contact shape) come straight from the pen,
// so pressure must feel right per participant, speed must not be faked by jitter at rest, and
// tilt must be true to the hand. The thesis used an Intuos4 (1024 pressure levels, §5.1.2,
// §7.4) through the Wacom API; here the raw samples come from drivers/.
//
// Smoothing runs in tablet millimetres, so its parameters do not depend on the screen or the
// mapping. Pure and deterministic: the same samples give the same output, which is what lets a
// replay of the journal's raw samples reproduce a session.
#pragma once

#include <cstdint>
#include <string>

#include "calibration/calibration_profile.h"
#include "calibration/contact_hysteresis.h"
#include "calibration/mapped_sample.h"
#include "calibration/nib_offset.h"
#include "calibration/one_euro_filter.h"
#include "calibration/pressure_curve.h"
#include "calibration/pressure_range.h"
#include "calibration/preview_predictor.h"
#include "drivers/core/pen_sample.h"

namespace cb {

class Calibrator {
 public:
  // `screen_w/h_px`: the display the pen maps to. Check ok()/error() afterwards: an invalid
  // area (e.g. a custom area outside this tablet) falls back to the whole area, with the error
  // kept for the operator.
  Calibrator(const CalibrationProfile& profile, const PenDeviceInfo& device, int screen_w_px,
             int screen_h_px);

  MappedSample process(const PenSample& sample);

  // Session: the participant's pressure range (default: the full range).
  void setPressureRange(const PressureRange& range) { range_ = range; }
  const PressureRange& pressureRange() const { return range_; }

  const CalibrationProfile& profile() const { return profile_; }
  // Tablet mm -> screen px, area mapping then N-point correction.
  const glm::dmat3& tabletToScreen() const { return tablet_to_screen_; }
  // The area mapping alone (what the N-point fit is measured against).
  const glm::dmat3& areaTransform() const { return area_transform_; }
  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  float nibOffset() const { return nib_.offset(); }
  // Samples whose position was not finite (the last good position was held).
  uint64_t rejectedSamples() const { return rejected_; }

 private:
  void resetFilters();

  CalibrationProfile profile_;
  PenDeviceInfo device_;
  glm::dmat3 area_transform_{1.0}, tablet_to_screen_{1.0};
  std::string error_;

  NibOffsetDetector nib_;
  ContactHysteresis contact_;
  PressureCurve curve_;
  PressureRange range_;
  OneEuroFilter<2> position_filter_, tilt_filter_;
  PreviewPredictor predictor_;

  bool in_proximity_ = false;
  double last_x_mm_ = 0.0, last_y_mm_ = 0.0;
  uint64_t rejected_ = 0;
};

}  // namespace cb
