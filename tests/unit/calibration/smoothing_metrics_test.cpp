#include "calibration/smoothing_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include "tests/support/test_seed.h"

namespace cb {
namespace {

std::vector<glm::dvec2> circle(int n, double dt, double speed, double radius, double delay_s) {
  std::vector<glm::dvec2> v;
  for (int i = 0; i < n; ++i) {
    const double ph = speed * (i * dt - delay_s) / radius;
    v.push_back({radius * std::cos(ph), radius * std::sin(ph)});
  }
  return v;
}

TEST(SmoothingMetrics, LagFindsKnownSubSampleDelays) {
  const double dt = 0.005;
  const auto truth = circle(600, dt, 300, 40, 0.0);
  for (double delay : {0.0, 0.0013, 0.0037, 0.0075, 0.012}) {
    const auto delayed = circle(600, dt, 300, 40, delay);
    EXPECT_NEAR(lagByCrossCorrelation(truth, delayed, dt, 100), delay, 0.0003) << delay;
  }
  // Noise does not bias it.
  std::mt19937_64 rng(test::testSeed("SmoothingMetrics lag under noise", 2));
  std::normal_distribution<double> noise(0.0, 0.05);
  auto noisy = circle(600, dt, 100, 40, 0.004);
  for (auto& p : noisy) p += glm::dvec2(noise(rng), noise(rng));
  EXPECT_NEAR(lagByCrossCorrelation(circle(600, dt, 100, 40, 0.0), noisy, dt, 100), 0.004, 0.0005);
}

TEST(SmoothingMetrics, JitterIsPerAxisStd) {
  std::mt19937_64 rng(test::testSeed("SmoothingMetrics.JitterIsPerAxisStd", 4));
  std::normal_distribution<double> noise(0.0, 0.05);
  std::vector<glm::dvec2> v;
  for (int i = 0; i < 20000; ++i) v.push_back({5 + noise(rng), 7 + noise(rng)});
  EXPECT_NEAR(jitterStdMm(v, 0), 0.05, 0.002);
}

TEST(SmoothingMetrics, PreviewErrorAgainstFutureTruth) {
  std::vector<TimedPoint> truth, preview;
  for (int i = 0; i < 100; ++i) {
    truth.push_back({i * 5'000'000LL, {i * 1.0, 0.0}});  // 200 mm/s
    preview.push_back({i * 5'000'000LL, {i * 1.0, 0.0}});
  }
  // Showing where the pen is now, 16 ms late: 3.2 mm behind.
  EXPECT_NEAR(previewErrorMm(truth, preview, 0.016, 0), 3.2, 1e-9);
  for (auto& p : preview) p.p.x += 3.2;
  EXPECT_NEAR(previewErrorMm(truth, preview, 0.016, 0), 0.0, 1e-9);
}

TEST(SmoothingMetrics, MovingAverageWindow) {
  MovingAverageFilter f(4);
  EXPECT_EQ(f.filter({4, 0}).x, 4.0);
  EXPECT_EQ(f.filter({8, 0}).x, 6.0);
  f.filter({0, 0});
  f.filter({0, 0});
  EXPECT_EQ(f.filter({0, 0}).x, 2.0);  // (8 + 0 + 0 + 0) / 4
}

}  // namespace
}  // namespace cb
