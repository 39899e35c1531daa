#include "calibration/pressure_curve.h"

#include <gtest/gtest.h>

#include <cmath>

namespace cb {
namespace {

TEST(PressureCurve, MonotonicWithFixedEndsForManyControlPoints) {
  const std::vector<std::array<double, 4>> curves = {
      {0, 0, 100, 100}, {0, 15, 85, 100}, {0, 35, 65, 100}, {15, 0, 100, 85},
      {0, 100, 0, 100}, {100, 0, 100, 0}, {100, 0, 0, 100}, {50, 50, 50, 50}};
  for (const auto& cp : curves) {
    PressureCurve c(cp);
    EXPECT_EQ(c.apply(0.0f), 0.0f);
    EXPECT_EQ(c.apply(1.0f), 1.0f);
    float prev = 0.0f;
    for (int i = 0; i <= 4000; ++i) {
      const float v = c.apply(i / 4000.0f);
      ASSERT_GE(v, prev) << "curve " << cp[0] << " " << cp[1] << " " << cp[2] << " " << cp[3]
                         << " at " << i / 4000.0;
      prev = v;
    }
  }
}

TEST(PressureCurve, LinearIsIdentitySoftIsAboveFirmIsBelow) {
  PressureCurve linear({0, 0, 100, 100}), soft({0, 40, 60, 100}), firm({40, 0, 100, 60});
  for (float p : {0.1f, 0.3f, 0.5f, 0.8f}) {
    EXPECT_NEAR(linear.apply(p), p, 1e-3);
    EXPECT_GT(soft.apply(p), p + 0.02f);
    EXPECT_LT(firm.apply(p), p - 0.02f);
  }
}

TEST(PressureCurve, ClampsAndHandlesNaN) {
  PressureCurve c({0, 15, 85, 100});
  EXPECT_EQ(c.apply(-0.5f), 0.0f);
  EXPECT_EQ(c.apply(2.0f), 1.0f);
  EXPECT_EQ(c.apply(NAN), 0.0f);
}

TEST(PressureCurve, ValidationNamesTheBadPoint) {
  EXPECT_TRUE(validatePressCurve({0, 0, 100, 100}).empty());
  const std::string e = validatePressCurve({0, 120, 100, 100});
  EXPECT_NE(e.find("y1"), std::string::npos) << e;
  EXPECT_FALSE(validatePressCurve({0, 0, NAN, 100}).empty());
}

}  // namespace
}  // namespace cb
