// Robust summaries of a sample for the study report, where one artefact (a pen report that jumps
// across the tablet in a millisecond) must not move the figure a reader takes away:
//
//   Quartiles by linear interpolation between order statistics (Hyndman & Fan 1996, type 7,
//     the default of R's quantile() and numpy's percentile): Q(p) = x[⌊h⌋] + (h − ⌊h⌋)(x[⌊h⌋+1]
//     − x[⌊h⌋]) with h = (n − 1)p over the sorted values (0-based).
//   IQR = Q3 − Q1.
//   Outliers: values beyond Tukey's outer fences, Q1 − 3·IQR and Q3 + 3·IQR ("far out",
//     Tukey 1977, Exploratory Data Analysis §2C); the inner fences (1.5·IQR) flag too many of
//     a skewed speed distribution's ordinary fast strokes to name each one.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

namespace cb {

struct RobustSummary {
  size_t n = 0;
  double median = 0, q1 = 0, q3 = 0, iqr = 0;
  double low_fence = 0, high_fence = 0;  // Tukey's outer fences
  double min = 0, max = 0;
  std::vector<size_t> outliers;  // indices (into the values given) beyond a fence, in order
};

// The type-7 quantile p (0..1) of `sorted` (ascending, non-empty).
double sortedQuantile(const std::vector<double>& sorted, double p);

// None for no values.
std::optional<RobustSummary> robustSummary(const std::vector<double>& values);

}  // namespace cb
