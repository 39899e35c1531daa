// The pressure curve: a cubic Bezier from (0,0) to (100,100) with two free control points, as
// xf86-input-wacom's PressCurve option ("x1 y1 x2 y2", each 0..100; "0 0 100 100" is linear,
// "0 15 85 100" softer, "15 0 100 85" firmer). Ends are fixed, so no pressure is lost at either
// end. Evaluated once into a lookup table; applying it is an interpolated table read.
//
//   B(t) = (1-t)^3 P0 + 3 (1-t)^2 t P1 + 3 (1-t) t^2 P2 + t^3 P3,  P0 = (0,0), P3 = (100,100)
//
// With both control points inside [0,100]^2 the x and y components are monotone in t, so the
// curve is a monotone function y(x); the table is built by solving x(t) = x for t (bisection).
#pragma once

#include <array>
#include <string>
#include <vector>

namespace cb {

class PressureCurve {
 public:
  static constexpr int kTableSize = 1025;

  PressureCurve() : PressureCurve({0, 0, 100, 100}) {}
  // Control points x1 y1 x2 y2 in 0..100. Out-of-range or non-finite points are clamped;
  // use validatePressCurve() first to report them.
  explicit PressureCurve(const std::array<double, 4>& control_points);

  // Maps a normalised pressure (clamped to 0..1) through the curve.
  float apply(float pressure) const;
  const std::array<double, 4>& controlPoints() const { return points_; }
  const std::vector<float>& table() const { return table_; }

 private:
  std::array<double, 4> points_;
  std::vector<float> table_;
};

// Empty when the points are valid, else what is wrong with them.
std::string validatePressCurve(const std::array<double, 4>& control_points);

}  // namespace cb
