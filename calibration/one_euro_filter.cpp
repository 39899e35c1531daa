#include "calibration/one_euro_filter.h"

#include <cmath>
#include <numbers>

namespace cb {

double oneEuroAlpha(double cutoff_hz, double dt_s) {
  const double tau = 1.0 / (2.0 * std::numbers::pi * cutoff_hz);
  return 1.0 / (1.0 + tau / dt_s);
}

template <size_t N>
typename OneEuroFilter<N>::Vec OneEuroFilter<N>::filter(const Vec& x, int64_t t_ns) {
  if (!primed_) {
    primed_ = true;
    last_t_ns_ = t_ns;
    last_raw_ = x;
    value_ = x;
    derivative_.fill(0.0);
    last_cutoff_hz_ = params_.min_cutoff_hz;
    return value_;
  }
  double dt = (t_ns - last_t_ns_) * 1e-9;
  if (dt <= 0.0) dt = last_dt_s_;  // repeated timestamp: assume the previous report interval
  last_dt_s_ = dt;
  last_t_ns_ = t_ns;

  const double alpha_d = oneEuroAlpha(params_.d_cutoff_hz, dt);
  double speed2 = 0.0;
  for (size_t i = 0; i < N; ++i) {
    const double dx = (x[i] - last_raw_[i]) / dt;
    derivative_[i] += alpha_d * (dx - derivative_[i]);
    speed2 += derivative_[i] * derivative_[i];
  }
  last_cutoff_hz_ = params_.min_cutoff_hz + params_.beta * std::sqrt(speed2);
  const double alpha = oneEuroAlpha(last_cutoff_hz_, dt);
  for (size_t i = 0; i < N; ++i) value_[i] += alpha * (x[i] - value_[i]);
  last_raw_ = x;
  return value_;
}

template class OneEuroFilter<1>;
template class OneEuroFilter<2>;

}  // namespace cb
