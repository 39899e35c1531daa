#include "calibration/smoothing_metrics.h"

#include <algorithm>
#include <cmath>

namespace cb {

double jitterStdMm(const std::vector<glm::dvec2>& output, size_t skip) {
  if (output.size() <= skip + 1) return 0.0;
  glm::dvec2 mean(0.0);
  for (size_t i = skip; i < output.size(); ++i) mean += output[i];
  mean /= static_cast<double>(output.size() - skip);
  double var = 0.0;
  for (size_t i = skip; i < output.size(); ++i) {
    const glm::dvec2 d = output[i] - mean;
    var += glm::dot(d, d);
  }
  var /= 2.0 * static_cast<double>(output.size() - skip - 1);
  return std::sqrt(var);
}

double lagByCrossCorrelation(const std::vector<glm::dvec2>& truth,
                             const std::vector<glm::dvec2>& output, double dt_s, size_t skip,
                             int max_shift) {
  const size_t n = std::min(truth.size(), output.size());
  if (n <= skip + 2 * static_cast<size_t>(max_shift) + 3) return 0.0;
  // Common window: output samples [lo, hi) whose shifted partners stay inside the truth.
  const size_t lo = std::max(skip, static_cast<size_t>(max_shift) + 1);
  const size_t hi = n - static_cast<size_t>(max_shift) - 1;
  // Cross-covariance with the means of exactly the samples each shift pairs up, so a window
  // that holds a fraction of a period does not tilt the peak.
  glm::dvec2 mo(0.0);
  for (size_t i = lo; i < hi; ++i) mo += output[i];
  mo /= static_cast<double>(hi - lo);
  auto corr = [&](int k) {
    glm::dvec2 mt(0.0);
    for (size_t i = lo; i < hi; ++i) mt += truth[i - k];
    mt /= static_cast<double>(hi - lo);
    double c = 0.0;
    for (size_t i = lo; i < hi; ++i) c += glm::dot(output[i] - mo, truth[i - k] - mt);
    return c;
  };
  std::vector<double> c(2 * max_shift + 1);
  for (int k = -max_shift; k <= max_shift; ++k) c[k + max_shift] = corr(k);
  int best = 0;
  for (int k = 1; k < static_cast<int>(c.size()); ++k)
    if (c[k] > c[best]) best = k;
  double frac = 0.0;
  if (best > 0 && best + 1 < static_cast<int>(c.size())) {
    const double a = c[best - 1], b = c[best], d = c[best + 1];
    const double denom = a - 2.0 * b + d;
    if (denom < 0.0) frac = 0.5 * (a - d) / denom;
  }
  return (best - max_shift + frac) * dt_s;
}

glm::dvec2 interpolateTruth(const std::vector<TimedPoint>& truth, int64_t t_ns) {
  if (truth.empty()) return glm::dvec2(0.0);
  if (t_ns <= truth.front().t_ns) return truth.front().p;
  if (t_ns >= truth.back().t_ns) return truth.back().p;
  auto it = std::lower_bound(truth.begin(), truth.end(), t_ns,
                             [](const TimedPoint& a, int64_t t) { return a.t_ns < t; });
  const TimedPoint& b = *it;
  const TimedPoint& a = *(it - 1);
  const double f = static_cast<double>(t_ns - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns);
  return a.p + f * (b.p - a.p);
}

double previewErrorMm(const std::vector<TimedPoint>& truth, const std::vector<TimedPoint>& preview,
                      double horizon_s, size_t skip) {
  if (truth.empty()) return 0.0;
  const int64_t h = static_cast<int64_t>(std::llround(horizon_s * 1e9));
  double sum = 0.0;
  size_t count = 0;
  for (size_t i = skip; i < preview.size(); ++i) {
    const int64_t t = preview[i].t_ns + h;
    if (t > truth.back().t_ns) break;
    sum += glm::length(preview[i].p - interpolateTruth(truth, t));
    ++count;
  }
  return count ? sum / count : 0.0;
}

glm::dvec2 MovingAverageFilter::filter(glm::dvec2 p) {
  history_.push_back(p);
  if (history_.size() > window_) history_.erase(history_.begin());
  glm::dvec2 sum(0.0);
  for (const auto& h : history_) sum += h;
  return sum / static_cast<double>(history_.size());
}

}  // namespace cb
