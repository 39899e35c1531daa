#include "app/brush/synthetic_strokes.h"

#include <algorithm>
#include <cmath>

namespace cb {
namespace {

// A dense polyline through the control points (uniform Catmull-Rom), with cumulative lengths.
struct Polyline {
  std::vector<glm::vec2> points;
  std::vector<float> cumulative;

  explicit Polyline(const std::vector<glm::vec2>& cp) {
    if (cp.size() == 1) {
      points = {cp[0]};
    } else {
      for (size_t i = 0; i + 1 < cp.size(); ++i) {
        glm::vec2 p0 = cp[i > 0 ? i - 1 : i], p1 = cp[i], p2 = cp[i + 1];
        glm::vec2 p3 = cp[i + 2 < cp.size() ? i + 2 : i + 1];
        for (int k = 0; k < 256; ++k) {
          float t = k / 256.0f, t2 = t * t, t3 = t2 * t;
          points.push_back(0.5f * (2.0f * p1 + (p2 - p0) * t +
                                   (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * t2 +
                                   (3.0f * p1 - p0 - 3.0f * p2 + p3) * t3));
        }
      }
      points.push_back(cp.back());
    }
    cumulative.assign(points.size(), 0.0f);
    for (size_t i = 1; i < points.size(); ++i)
      cumulative[i] = cumulative[i - 1] + glm::length(points[i] - points[i - 1]);
  }
  float length() const { return cumulative.back(); }
  glm::vec2 at(float s) const {
    if (points.size() == 1 || s <= 0.0f) return points.front();
    if (s >= length()) return points.back();
    size_t i =
        size_t(std::upper_bound(cumulative.begin(), cumulative.end(), s) - cumulative.begin());
    float seg = cumulative[i] - cumulative[i - 1];
    float f = seg > 0.0f ? (s - cumulative[i - 1]) / seg : 0.0f;
    return points[i - 1] + (points[i] - points[i - 1]) * f;
  }
};

}  // namespace

std::vector<BrushInput> sampleStroke(const SyntheticStroke& stroke, double rate_hz, int64_t t0_ns) {
  Polyline line(stroke.control_points);
  double duration = line.length() / stroke.speed_px_s;
  std::vector<BrushInput> out;
  auto emit = [&](double t) {
    float s = float(t * stroke.speed_px_s);
    float f = line.length() > 0.0f ? std::clamp(s / line.length(), 0.0f, 1.0f) : 0.0f;
    BrushInput in;
    in.footprint_px = line.at(s);
    in.pressure = stroke.pressure(f);
    in.tilt_x_deg = stroke.tilt_x_deg(f);
    in.tilt_y_deg = stroke.tilt_y_deg(f);
    in.t_ns = t0_ns + int64_t(std::llround(t * 1e9));
    out.push_back(in);
  };
  int n = int(std::floor(duration * rate_hz));
  for (int k = 0; k <= n; ++k) emit(k / rate_hz);
  if (double(n) / rate_hz < duration) emit(duration);
  return out;
}

SyntheticStroke pressureRamp(int w, int h) {
  SyntheticStroke s;
  s.name = "pressure_ramp";
  s.control_points = {{0.12f * w, 0.5f * h}, {0.88f * w, 0.5f * h}};
  s.pressure = [](float f) { return 0.05f + 0.95f * f; };
  return s;
}

SyntheticStroke tiltSweep(int w, int h) {
  SyntheticStroke s;
  s.name = "tilt_sweep";
  s.control_points = {{0.12f * w, 0.5f * h}, {0.88f * w, 0.5f * h}};
  s.pressure = [](float) { return 0.7f; };
  s.tilt_x_deg = [](float f) { return -50.0f + 100.0f * f; };
  s.tilt_y_deg = [](float f) { return 20.0f * std::sin(6.2831853f * f); };
  return s;
}

SyntheticStroke gentleCurve(int w, int h) {
  SyntheticStroke s;
  s.name = "gentle_curve";
  s.control_points = {
      {0.15f * w, 0.6f * h}, {0.35f * w, 0.3f * h}, {0.6f * w, 0.7f * h}, {0.85f * w, 0.4f * h}};
  s.pressure = [](float f) { return 0.3f + 0.6f * std::sin(3.14159265f * f); };
  s.tilt_x_deg = [](float f) { return 30.0f * f; };
  return s;
}

std::vector<SyntheticStroke> yongStrokes(int size) {
  float u = float(size);
  auto P = [u](float x, float y) { return glm::vec2(x * u, y * u); };
  // Start soft, press, ride the body, lift: the harmonious start and natural end of §5.1.
  auto body = [](float press) {
    return [press](float f) {
      float attack = std::min(1.0f, f / 0.15f), release = std::min(1.0f, (1.0f - f) / 0.2f);
      return std::max(0.05f, press * (0.35f + 0.65f * std::min(attack, release)));
    };
  };
  std::vector<SyntheticStroke> s(8);
  s[0] = {"dot", {P(0.46f, 0.08f), P(0.5f, 0.12f), P(0.53f, 0.17f)}, 150.0f, body(0.8f)};
  s[1] = {"horizontal", {P(0.28f, 0.3f), P(0.45f, 0.29f), P(0.62f, 0.28f)}, 250.0f, body(0.6f)};
  s[2] = {"vertical", {P(0.6f, 0.28f), P(0.6f, 0.55f), P(0.6f, 0.84f)}, 300.0f, body(0.7f)};
  s[3] = {"hook", {P(0.6f, 0.84f), P(0.56f, 0.86f), P(0.5f, 0.8f)}, 500.0f, [](float f) {
            return std::max(0.05f, 0.8f * (1.0f - f));
          }};
  s[4] = {"rise", {P(0.3f, 0.56f), P(0.42f, 0.5f), P(0.55f, 0.44f)}, 600.0f, [](float f) {
            return std::max(0.05f, 0.7f * (1.0f - 0.8f * f));
          }};
  s[5] = {"bend_left_fall",
          {P(0.32f, 0.42f), P(0.5f, 0.42f), P(0.36f, 0.62f), P(0.18f, 0.8f)},
          400.0f,
          body(0.55f)};
  s[6] = {
      "short_left_fall", {P(0.82f, 0.36f), P(0.72f, 0.44f), P(0.62f, 0.52f)}, 450.0f, body(0.5f)};
  s[7] = {"right_fall", {P(0.62f, 0.5f), P(0.72f, 0.64f), P(0.86f, 0.8f)}, 250.0f, [](float f) {
            return 0.2f + 0.75f * f * (f < 0.85f ? 1.0f : (1.0f - f) / 0.15f);
          }};
  for (int i = 0; i < 8; ++i) s[i].tilt_x_deg = [i](float) { return -15.0f + 4.0f * i; };
  return s;
}

}  // namespace cb
