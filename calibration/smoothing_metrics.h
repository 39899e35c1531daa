// Figures of merit for smoothing and prediction, measured against known ground truth.
//
// Jitter at rest: per-axis standard deviation of the output while the pen is still,
//   sqrt((var x + var y) / 2), in mm (comparable to the per-axis noise sigma).
// Lag: the delay d that best aligns output(t) with truth(t - d), found by cross-correlation of
//   the mean-removed 2D signals, C(k) = sum_i <out_i, truth_{i-k}>, over integer shifts k;
//   the peak is refined to a sub-sample delay by fitting a parabola through C(k-1), C(k),
//   C(k+1):  d = (k + (C(k-1) - C(k+1)) / (2 (C(k-1) - 2 C(k) + C(k+1)))) * dt.
// Preview error: mean distance between the preview at t and the truth at t + horizon (where
//   the pen is when the frame shows), truth linearly interpolated between samples.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace cb {

struct TimedPoint {
  int64_t t_ns = 0;
  glm::dvec2 p{0.0};
};

double jitterStdMm(const std::vector<glm::dvec2>& output, size_t skip);

// `truth` and `output` sampled at the same instants, spaced dt_s. Only samples from `skip` on
// count (filter start-up). Shifts searched: -max_shift..max_shift samples.
double lagByCrossCorrelation(const std::vector<glm::dvec2>& truth,
                             const std::vector<glm::dvec2>& output, double dt_s, size_t skip,
                             int max_shift = 40);

// Mean |preview_i - truth(t_i + horizon)| over samples from `skip` whose t + horizon lies
// inside the truth's time span.
double previewErrorMm(const std::vector<TimedPoint>& truth, const std::vector<TimedPoint>& preview,
                      double horizon_s, size_t skip);

// The truth at time t_ns (linear interpolation, clamped to the ends).
glm::dvec2 interpolateTruth(const std::vector<TimedPoint>& truth, int64_t t_ns);

// The baseline smoother: mean of the last `window` positions (xf86-input-wacom's RawSample,
// libinput's history), reset like the 1€ filter.
class MovingAverageFilter {
 public:
  explicit MovingAverageFilter(size_t window = 4) : window_(window) {}
  void reset() { history_.clear(); }
  glm::dvec2 filter(glm::dvec2 p);

 private:
  size_t window_;
  std::vector<glm::dvec2> history_;
};

}  // namespace cb
