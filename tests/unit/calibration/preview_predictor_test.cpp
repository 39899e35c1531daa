#include "calibration/preview_predictor.h"

#include <gtest/gtest.h>

namespace cb {
namespace {

TEST(PreviewPredictor, ExtrapolatesConstantVelocityByHorizon) {
  PredictionParams p;
  p.horizon_ms = 16;
  p.compensate_filter_lag = false;
  PreviewPredictor pred(p);
  std::array<double, 2> out{};
  for (int i = 0; i < 200; ++i) {  // 200 mm/s along x at 200 Hz
    out = pred.predict({i * 1.0, 5.0}, i * 5'000'000LL, 0.0);
  }
  EXPECT_NEAR(out[0], 199.0 + 200.0 * 0.016, 1e-6);
  EXPECT_NEAR(out[1], 5.0, 1e-9);
}

TEST(PreviewPredictor, CompensatesFilterLagAndCapsDistance) {
  PredictionParams p;
  p.horizon_ms = 16;
  p.compensate_filter_lag = true;
  p.max_distance_mm = 4.0;
  PreviewPredictor pred(p);
  std::array<double, 2> out{};
  for (int i = 0; i < 200; ++i) out = pred.predict({i * 1.0, 0.0}, i * 5'000'000LL, 0.004);
  EXPECT_NEAR(out[0], 199.0 + 4.0, 1e-6);  // 200 mm/s * 20 ms = 4 mm: at the cap
  p.max_distance_mm = 100.0;
  pred.setParams(p);
  out = pred.predict({200.0, 0.0}, 200 * 5'000'000LL, 0.004);
  EXPECT_NEAR(out[0], 200.0 + 200.0 * 0.020, 1e-6);
}

TEST(PreviewPredictor, AtRestPredictsWhereThePenIs) {
  PreviewPredictor pred;
  std::array<double, 2> out{};
  for (int i = 0; i < 50; ++i) out = pred.predict({7.0, 8.0}, i * 5'000'000LL, 0.01);
  EXPECT_DOUBLE_EQ(out[0], 7.0);
  EXPECT_DOUBLE_EQ(out[1], 8.0);
}

}  // namespace
}  // namespace cb
