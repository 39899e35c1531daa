#include "calibration/preview_predictor.h"

#include <cmath>

#include "calibration/one_euro_filter.h"

namespace cb {

std::array<double, 2> PreviewPredictor::predict(const std::array<double, 2>& filtered, int64_t t_ns,
                                                double filter_lag_s) {
  if (!primed_) {
    primed_ = true;
    last_t_ns_ = t_ns;
    last_ = filtered;
    velocity_ = {0.0, 0.0};
    return filtered;
  }
  double dt = (t_ns - last_t_ns_) * 1e-9;
  if (dt <= 0.0) dt = last_dt_s_;
  last_dt_s_ = dt;
  last_t_ns_ = t_ns;
  const double alpha = oneEuroAlpha(params_.velocity_cutoff_hz, dt);
  for (int i = 0; i < 2; ++i) {
    velocity_[i] += alpha * ((filtered[i] - last_[i]) / dt - velocity_[i]);
  }
  last_ = filtered;

  const double ahead_s =
      params_.horizon_ms * 1e-3 + (params_.compensate_filter_lag ? filter_lag_s : 0.0);
  double dx = velocity_[0] * ahead_s, dy = velocity_[1] * ahead_s;
  const double dist = std::hypot(dx, dy);
  if (dist > params_.max_distance_mm && dist > 0.0) {
    const double k = params_.max_distance_mm / dist;
    dx *= k;
    dy *= k;
  }
  return {filtered[0] + dx, filtered[1] + dy};
}

}  // namespace cb
