#include "app/brush/path_resampler.h"

#include <cmath>

namespace cb {
namespace {
constexpr float kPressureStep = 0.04f;
constexpr float kTiltStepDeg = 3.0f;
}  // namespace

PathResampler::PathResampler(float spacing_px, float speed_smoothing_ms)
    : spacing_(spacing_px), tau_s_(speed_smoothing_ms * 1e-3f) {}

void PathResampler::begin(const StrokePoint& first, std::vector<Dab>* out) {
  last_ = first;
  travelled_since_dab_ = 0.0f;
  arc_ = 0.0f;
  speed_ = 0.0f;
  out->push_back(
      {first.footprint_px, first.pressure, first.tilt_x_deg, first.tilt_y_deg, 0.0f, first.t_ns});
  last_dab_ = out->back();
}

void PathResampler::add(const StrokePoint& p, std::vector<Dab>* out) {
  size_t first_new = out->size();
  glm::vec2 a = last_.footprint_px, b = p.footprint_px;
  float length = glm::length(b - a);
  float dt = float(p.t_ns - last_.t_ns) * 1e-9f;
  float speed_before = speed_;
  if (dt > 0.0f) {
    // Exponential smoothing with a time constant: the same for any report rate.
    float alpha = tau_s_ > 0.0f ? 1.0f - std::exp(-dt / tau_s_) : 1.0f;
    speed_ += (length / dt - speed_) * alpha;
  }
  if (length > 0.0f) {
    float next = spacing_ - travelled_since_dab_;  // distance along this segment to the next dab
    while (next <= length) {
      float s = next / length;
      auto mix = [s](float u, float v) { return u + (v - u) * s; };
      out->push_back(
          {a + (b - a) * s, mix(last_.pressure, p.pressure), mix(last_.tilt_x_deg, p.tilt_x_deg),
           mix(last_.tilt_y_deg, p.tilt_y_deg), mix(speed_before, speed_),
           last_.t_ns + int64_t(std::llround(double(p.t_ns - last_.t_ns) * s)), arc_ + next});
      next += spacing_;
    }
    travelled_since_dab_ = length - (next - spacing_);
  }
  // A pen pressed or tilted in place still changes the mark (a dot swelling under pressure).
  if (out->size() > first_new) last_dab_ = out->back();
  bool changed_in_place = std::abs(p.pressure - last_dab_.pressure) >= kPressureStep ||
                          std::abs(p.tilt_x_deg - last_dab_.tilt_x_deg) >= kTiltStepDeg ||
                          std::abs(p.tilt_y_deg - last_dab_.tilt_y_deg) >= kTiltStepDeg;
  if (changed_in_place) {
    out->push_back({b, p.pressure, p.tilt_x_deg, p.tilt_y_deg, speed_, p.t_ns, arc_ + length});
    last_dab_ = out->back();
  }
  arc_ += length;
  last_ = p;
}

}  // namespace cb
