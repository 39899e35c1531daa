#include "calibration/contact_hysteresis.h"

#include <gtest/gtest.h>

#include <cmath>

#include <random>
#include "tests/support/test_seed.h"

namespace cb {
namespace {

int countTransitions(ContactHysteresis& h, const std::vector<float>& pressures) {
  int transitions = 0;
  bool state = h.down();
  for (float p : pressures) {
    const bool now = h.update(p);
    transitions += now != state;
    state = now;
  }
  return transitions;
}

TEST(ContactHysteresis, NoChatterOnNoisyConstantPressure) {
  std::mt19937_64 rng(test::testSeed("ContactHysteresis.NoChatterOnNoisyConstantPressure", 3));
  // A resting pen at various levels, including right at each threshold, with 0.5 % noise.
  for (float level : {0.01f, 0.02f, 0.03f, 0.05f, 0.2f}) {
    std::normal_distribution<float> noise(level, 0.005f);
    std::vector<float> p(4000);
    for (float& v : p) v = noise(rng);
    ContactHysteresis h;
    EXPECT_LE(countTransitions(h, p), 1) << "level " << level;
  }
}

TEST(ContactHysteresis, PlainThresholdWouldChatter) {
  // The same noise around a single 3 % threshold: the reason for hysteresis.
  std::mt19937_64 rng(test::testSeed("ContactHysteresis.PlainThresholdWouldChatter", 3));
  std::normal_distribution<float> noise(0.03f, 0.005f);
  ContactHysteresis single(ContactThresholds{0.03f, 0.03f});
  std::vector<float> p(4000);
  for (float& v : p) v = noise(rng);
  EXPECT_GT(countTransitions(single, p), 100);
}

TEST(ContactHysteresis, DownAtUpperUpAtLower) {
  ContactHysteresis h;  // libinput defaults 5 % / 1 %
  EXPECT_FALSE(h.update(0.049f));
  EXPECT_TRUE(h.update(0.05f));
  EXPECT_TRUE(h.update(0.011f));
  EXPECT_TRUE(h.update(0.01f));
  EXPECT_FALSE(h.update(0.009f));
  EXPECT_FALSE(h.update(NAN));
  EXPECT_TRUE(h.update(0.5f));
  h.reset();
  EXPECT_FALSE(h.down());
}

}  // namespace
}  // namespace cb
