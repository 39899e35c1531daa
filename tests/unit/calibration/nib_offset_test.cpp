#include "calibration/nib_offset.h"

#include <gtest/gtest.h>

#include <random>

#include "calibration/contact_hysteresis.h"
#include "tests/support/test_seed.h"

namespace cb {
namespace {

// A worn-nib trace: the pen enters proximity high above the tablet reporting ~8 % pressure in
// the air (noisy), descends, presses a stroke, rises and leaves.
std::vector<PenSample> wornNibTrace(float air_pressure, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<float> noise(0.0f, 0.004f);
  std::vector<PenSample> trace;
  auto add = [&](float distance, float pressure, bool touching) {
    PenSample s;
    s.t_ns = static_cast<int64_t>(trace.size()) * 5'000'000;
    s.in_proximity = true;
    s.distance = distance;
    s.pressure = std::max(0.0f, pressure + noise(rng));
    s.buttons = touching ? uint32_t{kPenTip} : 0u;
    trace.push_back(s);
  };
  for (int i = 0; i < 40; ++i) add(0.9f - i * 0.02f, air_pressure, false);  // hover, descending
  for (int i = 0; i < 20; ++i) add(0.05f, air_pressure, false);             // low hover
  for (int i = 0; i < 100; ++i) add(0.0f, air_pressure + 0.4f, true);       // stroke
  for (int i = 0; i < 40; ++i) add(0.1f + i * 0.02f, air_pressure, false);  // rise
  return trace;
}

TEST(NibOffset, DetectsWornNibWhileHoveringHighAndStopsPhantomStrokes) {
  const float air = 0.08f;
  auto trace = wornNibTrace(air, test::testSeed("NibOffset worn nib", 5));
  NibOffsetDetector nib;
  ContactHysteresis naive, corrected;
  int naive_down_while_hovering = 0, corrected_down_while_hovering = 0,
      corrected_down_in_stroke = 0;
  nib.proximityIn();
  for (size_t i = 0; i < trace.size(); ++i) {
    const PenSample& s = trace[i];
    nib.observe(s, /*has_distance=*/true);
    const bool nd = naive.update(s.pressure);
    const bool cd = corrected.update(nib.correct(s.pressure));
    const bool hovering = !s.tipDown();
    naive_down_while_hovering += nd && hovering;
    corrected_down_while_hovering += cd && hovering;
    corrected_down_in_stroke += cd && !hovering;
  }
  // Minimum of the noisy air pressure: a little below 8 %.
  EXPECT_NEAR(nib.offset(), air, 0.015);
  EXPECT_LT(nib.offset(), air);
  EXPECT_GT(naive_down_while_hovering, 50);  // without the offset the nib paints on its own
  EXPECT_EQ(corrected_down_while_hovering, 0);
  EXPECT_EQ(corrected_down_in_stroke, 100);
  EXPECT_FALSE(nib.rejected());
}

TEST(NibOffset, PressedAtProximityInIsRejected) {
  NibOffsetDetector nib;  // max offset 20 %
  nib.proximityIn();
  PenSample s;
  s.in_proximity = true;
  s.distance = 0.8f;
  s.pressure = 0.35f;
  nib.observe(s, true);
  EXPECT_TRUE(nib.rejected());
  EXPECT_EQ(nib.offset(), 0.0f);
}

TEST(NibOffset, LowHoverAndTouchingDoNotCount) {
  NibOffsetDetector nib;
  nib.proximityIn();
  PenSample s;
  s.in_proximity = true;
  s.distance = 0.1f;  // below hover_high_distance
  s.pressure = 0.1f;
  nib.observe(s, true);
  EXPECT_EQ(nib.offset(), 0.0f);
  s.distance = 0.9f;
  s.buttons = kPenTip;
  nib.observe(s, true);
  EXPECT_EQ(nib.offset(), 0.0f);
  // Without a distance axis, any non-touching in-proximity sample counts.
  s.buttons = 0;
  s.distance = 0.0f;
  nib.observe(s, false);
  EXPECT_FLOAT_EQ(nib.offset(), 0.1f);
}

TEST(NibOffset, NewWindowAtEachProximityIn) {
  NibOffsetDetector nib;
  PenSample s;
  s.in_proximity = true;
  s.distance = 0.9f;
  s.pressure = 0.06f;
  nib.proximityIn();
  nib.observe(s, true);
  EXPECT_FLOAT_EQ(nib.offset(), 0.06f);
  // A new nib: the next window measures less; the old offset does not stick.
  nib.proximityIn();
  EXPECT_FLOAT_EQ(nib.offset(), 0.06f);  // kept until the window sees a hovering sample
  s.pressure = 0.0f;
  nib.observe(s, true);
  EXPECT_FLOAT_EQ(nib.offset(), 0.0f);
  EXPECT_FLOAT_EQ(nib.correct(0.5f), 0.5f);
}

TEST(NibOffset, CorrectRescalesToFullRange) {
  NibOffsetDetector nib;
  PenSample s;
  s.in_proximity = true;
  s.distance = 0.9f;
  s.pressure = 0.1f;
  nib.proximityIn();
  nib.observe(s, true);
  EXPECT_FLOAT_EQ(nib.correct(0.1f), 0.0f);
  EXPECT_FLOAT_EQ(nib.correct(1.0f), 1.0f);
  EXPECT_NEAR(nib.correct(0.55f), 0.5f, 1e-6);
  EXPECT_EQ(nib.correct(0.05f), 0.0f);
  EXPECT_EQ(nib.correct(NAN), 0.0f);
}

}  // namespace
}  // namespace cb
