#include "calibration/tilt.h"

#include <gtest/gtest.h>

#include <cmath>

namespace cb {
namespace {

TEST(Tilt, AzimuthAltitude) {
  TiltAngles up = tiltToAzimuthAltitude(0, 0);
  EXPECT_FLOAT_EQ(up.altitude_deg, 90.0f);
  TiltAngles right = tiltToAzimuthAltitude(30, 0);
  EXPECT_NEAR(right.azimuth_deg, 0.0f, 1e-4);
  EXPECT_NEAR(right.altitude_deg, 60.0f, 1e-4);
  TiltAngles towards_user = tiltToAzimuthAltitude(0, 45);
  EXPECT_NEAR(towards_user.azimuth_deg, 90.0f, 1e-4);
  EXPECT_NEAR(towards_user.altitude_deg, 45.0f, 1e-4);
  TiltAngles left = tiltToAzimuthAltitude(-20, 0);
  EXPECT_NEAR(left.azimuth_deg, 180.0f, 1e-4);
  TiltAngles away = tiltToAzimuthAltitude(0, -20);
  EXPECT_NEAR(away.azimuth_deg, 270.0f, 1e-4);
  // Diagonal: equal tilts give 45°, and the altitude from the combined slope.
  TiltAngles diag = tiltToAzimuthAltitude(30, 30);
  EXPECT_NEAR(diag.azimuth_deg, 45.0f, 1e-4);
  EXPECT_NEAR(diag.altitude_deg, 50.768f, 1e-2);  // atan(1 / (sqrt(2) tan 30°))
  TiltAngles bad = tiltToAzimuthAltitude(NAN, 90);
  EXPECT_GE(bad.altitude_deg, 0.0f);
  EXPECT_LT(bad.altitude_deg, 1.0f);
}

}  // namespace
}  // namespace cb
