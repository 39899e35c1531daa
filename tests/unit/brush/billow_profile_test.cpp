// The brush's billowing edge (app/brush/billow_profile.h): a factor in [1 − A/3, 1 + A] whose
// mean along a long stroke lies between 1 and 1 + A/4 (lobes swell three times as far as necks
// narrow, so the size grows a little but keeps its meaning), which varies (a
// CV of the factor well above a tube's 0), changes smoothly from dab to dab, is exactly 1 at A = 0,
// and is the same for the same stroke index (a replay paints the same edge) and different for
// another.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "app/brush/billow_profile.h"
#include "tests/support/test_seed.h"

namespace cb {
namespace {

TEST(BillowProfile, StaysInItsRangeAveragesOneAndVariesSmoothly) {
  const uint32_t seed = test::testSeed("billow_profile_test");
  const float a = 0.6f, feature = 84.0f, step = 1.5f;  // brush.toml's billow and dab spacing
  double sum = 0, sum2 = 0, worst_step = 0;
  const int n = 200000;
  float last = billowFactor(seed, 0.0f, feature, a);
  for (int i = 0; i < n; ++i) {
    const float f = billowFactor(seed, float(i) * step, feature, a);
    ASSERT_GE(f, 1.0f - a / 3.0f) << i;
    ASSERT_LE(f, 1.0f + a) << i;
    sum += f;
    sum2 += double(f) * f;
    worst_step = std::max(worst_step, double(std::abs(f - last)));
    last = f;
  }
  const double mean = sum / n, cv = std::sqrt(sum2 / n - mean * mean) / mean;
  std::printf("seed %u: mean %.4f, cv %.3f, largest change between dabs %.4f\n", seed, mean, cv,
              worst_step);
  // Alternating lobes (strength 0.5–1, interpolated: mean swell about A/4 over half the
  // length) and necks a third as deep: the mean is above 1 and below 1 + A/4.
  EXPECT_GT(mean, 1.0);
  EXPECT_LT(mean, 1.0 + a / 4.0);
  EXPECT_GT(cv, 0.15) << "the edge hardly varies";
  // Smoothstep between lattice values in [-1, 1]: slope <= 2 · 1.5 per cell, times A, so a
  // dab step of step/feature cells changes the factor by <= 3A · step / feature. The arc is a
  // float: at the walk's far end (n · step px) two dabs' positions can be one ulp further apart
  // than the step (1/32 px at 300,000 px; seed 1056313390 reached 0.03216 against 0.03214).
  const float far = float(n) * step;
  const double ulp = double(std::nextafter(far, 2.0f * far) - far);
  EXPECT_LE(worst_step, 3.0 * a * (step + ulp) / feature + 1e-6);
}

TEST(BillowProfile, OffIsExactlyOneAndTheSeedDecides) {
  for (float arc : {0.0f, 13.0f, 1e5f}) EXPECT_EQ(billowFactor(3, arc, 80.0f, 0.0f), 1.0f);
  int same = 0, differ = 0;
  for (int i = 0; i < 100; ++i) {
    const float arc = float(i) * 37.0f;
    same += billowFactor(11, arc, 80.0f, 0.5f) == billowFactor(11, arc, 80.0f, 0.5f);
    differ += billowFactor(11, arc, 80.0f, 0.5f) != billowFactor(12, arc, 80.0f, 0.5f);
  }
  EXPECT_EQ(same, 100);
  EXPECT_GT(differ, 90);
}

}  // namespace
}  // namespace cb
