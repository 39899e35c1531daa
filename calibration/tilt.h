// Tilt: a per-device zero offset and the azimuth/altitude
// pair the 3D brush orients its cutting plane with (thesis §5.3, Fig. 5.7: tilt sets the plane's
// normal). Tilt x/y are angles from vertical in the x-z and y-z planes, +x right, +y towards
// the user (degrees from the axis resolution are computed once, by the drivers:
// drivers/core/pen_units.h); azimuth is measured clockwise from +x on the tablet (y down), altitude
// from the tablet surface (90 = upright), as in the W3C Pointer Events conversion.
#pragma once

#include <cstdint>

namespace cb {

struct TiltZero {
  float x_deg = 0.0f, y_deg = 0.0f;  // what the pen reports when held upright
};

struct TiltAngles {
  float azimuth_deg = 0.0f;    // 0..360, clockwise from +x
  float altitude_deg = 90.0f;  // 0 (flat) .. 90 (upright)
};

// tan(tilt_x) and tan(tilt_y) are the pen direction's slopes; tilts are clamped to ±89.9°.
TiltAngles tiltToAzimuthAltitude(float tilt_x_deg, float tilt_y_deg);

}  // namespace cb
