// The 1€ filter (Casiez, Roussel, Vogel, "1€ Filter: A Simple Speed-based Low-pass Filter for
// Noisy Input in Interactive Systems", CHI 2012): an exponential low-pass filter whose cutoff
// rises with speed, so the pen is steady at rest and does not trail in fast strokes.
//
//   tau(fc) = 1 / (2 pi fc),   alpha(fc, dt) = 1 / (1 + tau / dt)
//   dx      = (x_i - x_{i-1}) / dt                    (raw derivative)
//   dx^_i   = dx^_{i-1} + alpha(d_cutoff, dt) (dx - dx^_{i-1})
//   fc      = min_cutoff + beta * |dx^_i|
//   x^_i    = x^_{i-1} + alpha(fc, dt) (x_i - x^_{i-1})
//
// Here the filter is vector valued: one cutoff from the norm of the derivative is shared by all
// components, so a diagonal stroke is smoothed exactly like a horizontal one (filtering x and y
// separately would bend curves towards the slower axis).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace cb {

struct OneEuroParams {
  double min_cutoff_hz = 1.0;  // cutoff at rest: lower = steadier
  double beta = 0.0;           // cutoff gain per unit/s of speed: higher = less lag in motion
  double d_cutoff_hz = 1.0;    // cutoff of the derivative estimate
};

// Smoothing factor of an exponential filter with cutoff `cutoff_hz` at time step `dt_s`.
double oneEuroAlpha(double cutoff_hz, double dt_s);

template <size_t N>
class OneEuroFilter {
 public:
  using Vec = std::array<double, N>;

  OneEuroFilter() = default;
  explicit OneEuroFilter(const OneEuroParams& params) : params_(params) {}

  void setParams(const OneEuroParams& params) { params_ = params; }
  const OneEuroParams& params() const { return params_; }
  // Forget the history: the next sample passes through unchanged (proximity-in, tip-down).
  void reset() { primed_ = false; }
  bool primed() const { return primed_; }

  // Filters `x` observed at `t_ns`. A timestamp that does not advance reuses the last step.
  Vec filter(const Vec& x, int64_t t_ns);

  // The cutoff used for the last sample (Hz) and its time constant (s).
  double lastCutoffHz() const { return last_cutoff_hz_; }
  const Vec& value() const { return value_; }

 private:
  OneEuroParams params_;
  bool primed_ = false;
  int64_t last_t_ns_ = 0;
  double last_dt_s_ = 0.005;
  Vec last_raw_{};
  Vec value_{};
  Vec derivative_{};
  double last_cutoff_hz_ = 0.0;
};

extern template class OneEuroFilter<1>;
extern template class OneEuroFilter<2>;

}  // namespace cb
