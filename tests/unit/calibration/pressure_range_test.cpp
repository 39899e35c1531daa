#include "calibration/pressure_range.h"

#include <gtest/gtest.h>

#include <cmath>

namespace cb {
namespace {

std::vector<float> around(float level, int n) {
  std::vector<float> v;
  for (int i = 0; i < n; ++i) v.push_back(level + 0.01f * ((i % 5) - 2));
  return v;
}

TEST(PressureRange, LightHandedParticipantReachesFullInk) {
  PressureRangeFit fit = fitPressureRange(around(0.12f, 60), around(0.45f, 60), 0.2f);
  ASSERT_TRUE(fit.range) << fit.error;
  EXPECT_NEAR(fit.range->apply(0.12f), 0.2f, 0.03f);  // light press lands at the target
  EXPECT_GE(fit.range->apply(0.47f), 0.99f);          // firm press reaches full ink
  EXPECT_EQ(fit.range->apply(0.0f), 0.0f);
}

TEST(PressureRange, MonotoneAndClamped) {
  PressureRange r{0.1f, 0.6f};
  float prev = -1.0f;
  for (int i = 0; i <= 100; ++i) {
    const float v = r.apply(i / 100.0f);
    EXPECT_GE(v, prev);
    EXPECT_GE(v, 0.0f);
    EXPECT_LE(v, 1.0f);
    prev = v;
  }
  EXPECT_EQ(r.apply(NAN), 0.0f);
}

TEST(PressureRange, BadCalibrationSaysWhy) {
  PressureRangeFit few = fitPressureRange(around(0.1f, 3), around(0.5f, 60));
  EXPECT_FALSE(few.range);
  EXPECT_NE(few.error.find("too few"), std::string::npos);
  PressureRangeFit same = fitPressureRange(around(0.3f, 60), around(0.31f, 60));
  EXPECT_FALSE(same.range);
  EXPECT_NE(same.error.find("press harder"), std::string::npos) << same.error;
}

TEST(PressureRange, SessionTextRoundTrips) {
  PressureRange r{0.0625f, 0.4375f};
  std::string err;
  auto back = pressureRangeFromToml(pressureRangeToToml(r), &err);
  ASSERT_TRUE(back) << err;
  EXPECT_EQ(back->lo, r.lo);
  EXPECT_EQ(back->hi, r.hi);
  EXPECT_FALSE(pressureRangeFromToml("[pressure_range]\nlo = 0.5\nhi = 0.2\n", &err));
  EXPECT_FALSE(pressureRangeFromToml("[pressure_range\n", &err));
  EXPECT_NE(err.find("line 1"), std::string::npos) << err;
}

TEST(PressureRange, CollectorWalksLightThenFirm) {
  PressureRangeCollector c(20, 0.2f);
  auto press = [&](float level, int n) {
    for (int i = 0; i < n; ++i) c.feed(true, level + 0.005f * ((i % 3) - 1));
    c.feed(false, 0.0f);
  };
  press(0.15f, 5);  // too short: still the light step
  EXPECT_EQ(c.step(), PressureRangeCollector::Step::kLight);
  press(0.15f, 30);
  EXPECT_EQ(c.step(), PressureRangeCollector::Step::kFirm);
  press(0.6f, 30);
  ASSERT_EQ(c.step(), PressureRangeCollector::Step::kDone);
  ASSERT_TRUE(c.result().range) << c.result().error;
  EXPECT_NEAR(c.result().range->apply(0.15f), 0.2f, 0.02f);
  EXPECT_NEAR(c.result().range->hi, 0.605f, 0.006f);
  c.restart();
  EXPECT_EQ(c.step(), PressureRangeCollector::Step::kLight);
}

}  // namespace
}  // namespace cb
