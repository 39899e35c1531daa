#include "app/study/robust_statistics.h"

#include <algorithm>
#include <cmath>

namespace cb {

double sortedQuantile(const std::vector<double>& sorted, double p) {
  const double h = double(sorted.size() - 1) * std::clamp(p, 0.0, 1.0);
  const size_t lo = size_t(std::floor(h));
  const size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (h - double(lo)) * (sorted[hi] - sorted[lo]);
}

std::optional<RobustSummary> robustSummary(const std::vector<double>& values) {
  if (values.empty()) return std::nullopt;
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  RobustSummary s;
  s.n = values.size();
  s.min = sorted.front();
  s.max = sorted.back();
  s.median = sortedQuantile(sorted, 0.5);
  s.q1 = sortedQuantile(sorted, 0.25);
  s.q3 = sortedQuantile(sorted, 0.75);
  s.iqr = s.q3 - s.q1;
  s.low_fence = s.q1 - 3.0 * s.iqr;
  s.high_fence = s.q3 + 3.0 * s.iqr;
  for (size_t i = 0; i < values.size(); ++i)
    if (values[i] < s.low_fence || values[i] > s.high_fence) s.outliers.push_back(i);
  return s;
}

}  // namespace cb
