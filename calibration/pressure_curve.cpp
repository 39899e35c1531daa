#include "calibration/pressure_curve.h"

#include <algorithm>
#include <cmath>

namespace cb {
namespace {

// One component of the Bezier with P0 = 0 and P3 = 100.
double bezier(double p1, double p2, double t) {
  const double s = 1.0 - t;
  return 3.0 * s * s * t * p1 + 3.0 * s * t * t * p2 + t * t * t * 100.0;
}

double clampPoint(double v) {
  return std::isfinite(v) ? std::clamp(v, 0.0, 100.0) : 0.0;
}

}  // namespace

std::string validatePressCurve(const std::array<double, 4>& p) {
  for (size_t i = 0; i < p.size(); ++i) {
    if (!std::isfinite(p[i]) || p[i] < 0.0 || p[i] > 100.0) {
      static const char* names[] = {"x1", "y1", "x2", "y2"};
      return std::string("pressure curve control point ") + names[i] + " = " +
             std::to_string(p[i]) + " is outside 0..100";
    }
  }
  return {};
}

PressureCurve::PressureCurve(const std::array<double, 4>& control_points) {
  for (size_t i = 0; i < 4; ++i) points_[i] = clampPoint(control_points[i]);
  const double x1 = points_[0], y1 = points_[1], x2 = points_[2], y2 = points_[3];
  table_.resize(kTableSize);
  for (int i = 0; i < kTableSize; ++i) {
    const double x = 100.0 * i / (kTableSize - 1);
    double lo = 0.0, hi = 1.0;  // x(t) is monotone: bisect for x(t) = x
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (bezier(x1, x2, mid) < x ? lo : hi) = mid;
    }
    table_[i] = static_cast<float>(bezier(y1, y2, 0.5 * (lo + hi)) / 100.0);
  }
  // Fixed ends and monotone by construction; enforce both against rounding.
  table_.front() = 0.0f;
  table_.back() = 1.0f;
  for (int i = 1; i < kTableSize; ++i) table_[i] = std::clamp(table_[i], table_[i - 1], 1.0f);
}

float PressureCurve::apply(float pressure) const {
  if (!(pressure > 0.0f)) return 0.0f;  // also maps NaN to 0
  if (pressure >= 1.0f) return 1.0f;
  const float pos = pressure * (kTableSize - 1);
  const int i = static_cast<int>(pos);
  const float f = pos - i;
  return table_[i] + f * (table_[i + 1] - table_[i]);
}

}  // namespace cb
