// Prediction for what is drawn under the pen (cursor, brush preview) only: the filtered
// position extrapolated along the filtered velocity by a horizon, so the preview lands where
// the pen will be when the frame reaches the eye. The footprint never uses it.
//
//   v_i      = (p^_i - p^_{i-1}) / dt                 velocity of the 1€ output
//   v^_i     = v^_{i-1} + alpha(velocity_cutoff, dt) (v_i - v^_{i-1})
//   preview  = p^_i + v^_i * (horizon + lag)          capped at max_distance
//
// `lag` is the 1€ filter's own delay at its current cutoff (its time constant 1/(2 pi fc),
// the delay of an exponential filter on a ramp) when compensate_filter_lag is set, so the
// preview is extrapolated from where the pen is, not from where the filtered trace is.
#pragma once

#include <array>
#include <cstdint>

namespace cb {

struct PredictionParams {
  double horizon_ms = 16.0;          // on real hardware: the display's input-to-photon latency
  double velocity_cutoff_hz = 20.0;  // smoothing of the velocity estimate
  bool compensate_filter_lag = true;
  double max_distance_mm = 15.0;  // never extrapolate further than this
};

class PreviewPredictor {
 public:
  PreviewPredictor() = default;
  explicit PreviewPredictor(const PredictionParams& params) : params_(params) {}
  void setParams(const PredictionParams& params) { params_ = params; }
  const PredictionParams& params() const { return params_; }
  void reset() { primed_ = false; }

  // `filtered` is the 1€ output (mm) at `t_ns`; `filter_lag_s` its current time constant.
  std::array<double, 2> predict(const std::array<double, 2>& filtered, int64_t t_ns,
                                double filter_lag_s);
  const std::array<double, 2>& velocity() const { return velocity_; }

 private:
  PredictionParams params_;
  bool primed_ = false;
  int64_t last_t_ns_ = 0;
  double last_dt_s_ = 0.005;
  std::array<double, 2> last_{}, velocity_{};
};

}  // namespace cb
