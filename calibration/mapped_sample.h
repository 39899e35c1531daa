// MappedSample: what calibration/ hands to the app for every PenSample. Screen position (for
// the footprint), a predicted position (for the cursor and brush preview only), calibrated
// pressure and contact, tilt in degrees with azimuth/altitude, and the raw sample it came from
// (the journal keeps raw samples, so a replay re-derives all of this).
#pragma once

#include <cstdint>

#include "drivers/core/pen_sample.h"

namespace cb {

struct MappedSample {
  int64_t t_ns = 0;

  // Filtered (1€), unpredicted screen position in pixels, y down: what the footprint uses.
  double x_px = 0.0, y_px = 0.0;
  // Extrapolated by the prediction horizon: for what is drawn under the pen (cursor, preview)
  // only, never for the footprint.
  double preview_x_px = 0.0, preview_y_px = 0.0;

  // Pressure after nib offset, participant range and pressure curve, 0..1.
  float pressure = 0.0f;
  // Pressure after the nib offset only, 0..1: what the participant's light/firm press range is
  // measured in (calibration/pressure_range.h).
  float pressure_corrected = 0.0f;
  // Contact after hysteresis (down at the upper threshold, up at the lower one).
  bool contact = false;
  bool contact_began = false;  // this sample put the pen down
  bool contact_ended = false;  // this sample lifted it (also on proximity out while down)
  // In contact only through the hysteresis: the pressure is below the down threshold (a pen
  // resting lightly; it would not have gone down at this pressure). Never for pens without
  // pressure. The painter ends a stroke left resting lightly (§7.7.5 problem 3).
  bool light_contact = false;

  bool in_proximity = false;
  bool proximity_began = false;

  // Tilt from vertical after the device's zero offset and the 1€ filter, +x right, +y towards
  // the user; azimuth clockwise from +x (0..360), altitude 90 = upright.
  float tilt_x_deg = 0.0f, tilt_y_deg = 0.0f;
  float azimuth_deg = 0.0f, altitude_deg = 90.0f;

  PenSample raw;  // the sample as the driver reported it
};

}  // namespace cb
