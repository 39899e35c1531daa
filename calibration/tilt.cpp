#include "calibration/tilt.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cb {

TiltAngles tiltToAzimuthAltitude(float tilt_x_deg, float tilt_y_deg) {
  constexpr double kDeg = std::numbers::pi / 180.0;
  if (!std::isfinite(tilt_x_deg)) tilt_x_deg = 0.0f;
  if (!std::isfinite(tilt_y_deg)) tilt_y_deg = 0.0f;
  const double tx = std::tan(std::clamp<double>(tilt_x_deg, -89.9, 89.9) * kDeg);
  const double ty = std::tan(std::clamp<double>(tilt_y_deg, -89.9, 89.9) * kDeg);
  const double slope = std::hypot(tx, ty);
  TiltAngles a;
  if (slope == 0.0) return a;  // upright: azimuth undefined, report 0
  double az = std::atan2(ty, tx) / kDeg;
  if (az < 0.0) az += 360.0;
  a.azimuth_deg = static_cast<float>(az);
  a.altitude_deg = static_cast<float>(std::atan(1.0 / slope) / kDeg);
  return a;
}

}  // namespace cb
