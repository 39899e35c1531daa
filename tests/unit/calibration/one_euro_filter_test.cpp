#include "calibration/one_euro_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include "tests/support/test_seed.h"

namespace cb {
namespace {

constexpr int64_t kStep = 5'000'000;  // 200 Hz

TEST(OneEuroFilter, FirstSamplePassesAndResetForgets) {
  OneEuroFilter<2> f(OneEuroParams{1.0, 0.0, 1.0});
  auto v = f.filter({3.0, 4.0}, 0);
  EXPECT_EQ(v[0], 3.0);
  v = f.filter({13.0, 4.0}, kStep);
  EXPECT_GT(v[0], 3.0);
  EXPECT_LT(v[0], 13.0);
  f.reset();
  v = f.filter({-1.0, -1.0}, 2 * kStep);
  EXPECT_EQ(v[0], -1.0);
  EXPECT_EQ(v[1], -1.0);
}

TEST(OneEuroFilter, MatchesExponentialFilterWhenBetaIsZero) {
  const double fc = 2.0, dt = 0.005;
  OneEuroFilter<1> f(OneEuroParams{fc, 0.0, 1.0});
  const double a = oneEuroAlpha(fc, dt);
  EXPECT_NEAR(a, 1.0 / (1.0 + 1.0 / (2 * M_PI * fc * dt)), 1e-15);
  double ref = 0.0;
  f.filter({0.0}, 0);
  for (int i = 1; i < 100; ++i) {
    const double x = std::sin(i * 0.1);
    ref += a * (x - ref);
    EXPECT_NEAR(f.filter({x}, i * kStep)[0], ref, 1e-12);
  }
}

TEST(OneEuroFilter, SteadyAtRestFastInMotion) {
  std::mt19937_64 rng(test::testSeed("OneEuroFilter.SteadyAtRestFastInMotion", 1));
  std::normal_distribution<double> noise(0.0, 0.05);
  OneEuroFilter<2> f(OneEuroParams{1.0, 0.1, 1.0});
  // At rest: output spread much smaller than the input's.
  double sum2 = 0.0;
  int n = 0;
  for (int i = 0; i < 600; ++i) {
    auto v = f.filter({noise(rng), noise(rng)}, i * kStep);
    if (i > 200) sum2 += v[0] * v[0], ++n;
  }
  EXPECT_LT(std::sqrt(sum2 / n), 0.05 / 5);
  // In a fast ramp the cutoff rises with speed.
  const double rest_cutoff = f.lastCutoffHz();
  for (int i = 600; i < 800; ++i) f.filter({(i - 600) * 1.5, 0.0}, i * kStep);  // 300 mm/s
  EXPECT_GT(f.lastCutoffHz(), 10 * rest_cutoff);
}

TEST(OneEuroFilter, VectorFilterKeepsDirection) {
  // A diagonal ramp stays on the diagonal: one shared cutoff for both axes.
  OneEuroFilter<2> f(OneEuroParams{1.0, 0.05, 1.0});
  for (int i = 0; i < 100; ++i) {
    auto v = f.filter({i * 1.0, i * 0.5}, i * kStep);
    EXPECT_NEAR(v[1], v[0] * 0.5, 1e-9);
  }
}

TEST(OneEuroFilter, RepeatedTimestampDoesNotDivideByZero) {
  OneEuroFilter<1> f(OneEuroParams{1.0, 0.1, 1.0});
  f.filter({0.0}, 0);
  auto v = f.filter({1.0}, 0);
  EXPECT_TRUE(std::isfinite(v[0]));
}

}  // namespace
}  // namespace cb
