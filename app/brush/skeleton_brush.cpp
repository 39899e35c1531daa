#include "app/brush/skeleton_brush.h"

#include <algorithm>
#include <cmath>

#include "app/brush/hash_noise.h"
#include "app/brush/sample_splat.h"

namespace cb {
namespace {
constexpr int kJoints = 4;
constexpr float kRestLeanDeg = 12.0f;  // a brush never hangs perfectly plumb: folds one way
constexpr float kMovedEpsPx = 0.05f;   // re-stamp bristles only after the spine moved this much
constexpr int kSettleSteps = 40;       // steps to let the spine settle at tip-down
constexpr float kMinSpan = 0.9f;       // bending stiffness, as a fraction of a straight span

glm::vec3 cubicBezier(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3, float t) {
  float s = 1.0f - t;
  return s * s * s * p0 + 3.0f * s * s * t * p1 + 3.0f * s * t * t * p2 + t * t * t * p3;
}
StrokePoint lerpPoint(const StrokePoint& a, const StrokePoint& b, float s) {
  StrokePoint p = b;
  p.footprint_px = a.footprint_px + (b.footprint_px - a.footprint_px) * s;
  p.pressure = a.pressure + (b.pressure - a.pressure) * s;
  p.tilt_x_deg = a.tilt_x_deg + (b.tilt_x_deg - a.tilt_x_deg) * s;
  p.tilt_y_deg = a.tilt_y_deg + (b.tilt_y_deg - a.tilt_y_deg) * s;
  return p;
}
}  // namespace

SkeletonBrush::SkeletonBrush(const BrushConfig& c)
    : params_(c.skeleton),
      dispersion_params_(c.dispersion),
      dt_ns_(std::max<int64_t>(1, std::llround(double(c.skeleton.time_step_ms) * 1e6))) {}

float SkeletonBrush::reachPx() const {
  return 3.0f * params_.segment_length_px +
         params_.bristle_spread_px * (1.0f + params_.bristle_splay) + params_.bristle_radius_px +
         2.0f;
}

glm::vec3 SkeletonBrush::rodPosition(const StrokePoint& p) const {
  // The rod's foot: above the pen tip, lowered by pressure (§5.2.1: "its y value is defined by
  // the pressure"); at pressure 0 the hanging spine just reaches the paper.
  float spine = 3.0f * params_.segment_length_px;
  float height = spine * std::cos(glm::radians(kRestLeanDeg)) *
                 (1.0f - params_.press_depth * std::clamp(p.pressure, 0.0f, 1.0f));
  return {p.footprint_px.x, height, p.footprint_px.y};
}

glm::vec3 SkeletonBrush::acceleration(const StrokePoint& p) const {
  // V_acc: down, and away from the pen's lean (the bristles trail under a tilted rod).
  float lean_x = std::sin(glm::radians(std::clamp(p.tilt_x_deg, -60.0f, 60.0f)));
  float lean_z = std::sin(glm::radians(std::clamp(p.tilt_y_deg, -60.0f, 60.0f)));
  glm::vec3 dir(-lean_x - std::sin(glm::radians(kRestLeanDeg)), -1.0f, -lean_z);
  return glm::normalize(dir) * params_.gravity_px_s2;
}

void SkeletonBrush::prepareStroke(uint32_t stroke_index) {
  field_.reset(stroke_index, dispersion_params_.noise_scale_px);
}

FootprintRect SkeletonBrush::beginStroke(uint32_t stroke_index, const StrokePoint& first,
                                         Footprint* fp) {
  field_.reset(stroke_index, dispersion_params_.noise_scale_px);
  SeededRandom rng(hashCombine(params_.seed, int32_t(stroke_index)));
  bristles_.resize(size_t(params_.bristles));
  for (Bristle& b : bristles_) {
    float angle = rng.uniform(0.0f, 6.2831853f);
    float radius = std::sqrt(rng.uniform());
    b.offset = radius * glm::vec2(std::cos(angle), std::sin(angle));
    b.length = rng.uniform(0.75f, 1.0f);
  }
  // Rest pose: hang from the rod along V_acc down to the paper, then lie along the paper in
  // the trailing direction; then let it settle.
  glm::vec3 rod = rodPosition(first);
  glm::vec3 down = glm::normalize(acceleration(first));
  glm::vec3 trail = glm::normalize(glm::vec3(down.x, 0.0f, down.z));
  float to_paper = down.y < 0.0f ? rod.y / -down.y : 0.0f;
  for (int k = 0; k < kJoints; ++k) {
    float s = float(k) * params_.segment_length_px;
    joints_[k] = s <= to_paper ? rod + down * s : rod + down * to_paper + trail * (s - to_paper);
    previous_[k] = joints_[k];
  }
  last_input_ = first;
  sim_t_ns_ = first.t_ns;
  speed_px_s_ = 0.0f;
  for (int i = 0; i < kSettleSteps; ++i) step(first);
  stamped_joints_ = joints_;
  return stampBristles(first.pressure, fp);
}

FootprintRect SkeletonBrush::continueStroke(const StrokePoint& point, Footprint* fp) {
  FootprintRect changed;
  int64_t span = point.t_ns - last_input_.t_ns;
  if (span > 0) {
    float seg_speed = glm::length(point.footprint_px - last_input_.footprint_px) / (span * 1e-9f);
    float tau = dispersion_params_.speed_smoothing_ms * 1e-3f;
    float alpha = tau > 0.0f ? 1.0f - std::exp(-span * 1e-9f / tau) : 1.0f;
    speed_px_s_ += (seg_speed - speed_px_s_) * alpha;
  }
  int64_t steps = (point.t_ns - sim_t_ns_) / dt_ns_;
  if (steps > params_.max_steps_per_sample) {
    sim_t_ns_ += (steps - params_.max_steps_per_sample) * dt_ns_;  // the pen rested meanwhile
    steps = params_.max_steps_per_sample;
  }
  for (int64_t i = 0; i < steps; ++i) {
    sim_t_ns_ += dt_ns_;
    float s =
        span > 0 ? std::clamp(float(sim_t_ns_ - last_input_.t_ns) / float(span), 0.0f, 1.0f) : 1.0f;
    changed = changed.united(stepAndStamp(lerpPoint(last_input_, point, s), fp));
  }
  last_input_ = point;
  return changed;
}

FootprintRect SkeletonBrush::stepAndStamp(const StrokePoint& pen, Footprint* fp) {
  step(pen);
  float moved = 0.0f;
  for (int k = 0; k < kJoints; ++k)
    moved = std::max(moved, glm::length(joints_[k] - stamped_joints_[k]));
  if (moved < kMovedEpsPx) return {};
  // Resampled along the spine's path: a fast pen moves the spine several pixels per step, and
  // bristles stamped once per step left a dotted row (skeleton.stamp_spacing_px).
  FootprintRect changed;
  const float spacing = params_.stamp_spacing_px;
  const int between = spacing > 0.0f ? int(std::ceil(moved / spacing)) - 1 : 0;
  const std::array<glm::vec3, 4> to = joints_;
  for (int j = 1; j <= between; ++j) {
    const float f = float(j) / float(between + 1);
    for (int k = 0; k < kJoints; ++k)
      joints_[k] = stamped_joints_[k] + (to[k] - stamped_joints_[k]) * f;
    changed = changed.united(stampBristles(pen.pressure, fp));
  }
  joints_ = to;
  stamped_joints_ = joints_;
  return changed.united(stampBristles(pen.pressure, fp));
}

FootprintRect SkeletonBrush::endStroke(Footprint* fp) {
  // The brush comes to rest where the pen lifts (a calligrapher's stroke ends pressed under the
  // nib; the trailing bristles catch up), so the stroke's ink reaches its end.
  FootprintRect changed;
  for (int i = 0; i < params_.end_settle_steps; ++i)
    changed = changed.united(stepAndStamp(last_input_, fp));
  return changed;
}

void SkeletonBrush::step(const StrokePoint& pen) {
  float dt = float(dt_ns_) * 1e-9f;
  glm::vec3 a = acceleration(pen);
  // Position Verlet (§5.2.1, corrected): x' = x + (1 − damping)(x − x_prev) + a·dt².
  previous_[0] = joints_[0];
  joints_[0] = rodPosition(pen);
  for (int k = 1; k < kJoints; ++k) {
    glm::vec3 x = joints_[k];
    joints_[k] = x + (1.0f - params_.damping) * (x - previous_[k]) + a * dt * dt;
    previous_[k] = x;
  }
  const float L = params_.segment_length_px, floor_y = -params_.paper_softness_px;
  for (int it = 0; it < params_.constraint_iterations; ++it) {
    for (int k = 0; k + 1 < kJoints; ++k) {
      glm::vec3 delta = joints_[k + 1] - joints_[k];
      float d = glm::length(delta);
      if (d < 1e-6f) continue;
      glm::vec3 fix = delta * ((d - L) / d);
      if (k == 0) {
        joints_[1] -= fix;  // joint 0 is held by the pen
      } else {
        joints_[k] += 0.5f * fix;
        joints_[k + 1] -= 0.5f * fix;
      }
    }
    // Bristle stiffness: joints two apart keep at least kMinSpan·2L, so the spine bends but
    // never folds back on itself.
    for (int k = 0; k + 2 < kJoints; ++k) {
      glm::vec3 delta = joints_[k + 2] - joints_[k];
      float d = glm::length(delta), min_span = kMinSpan * 2.0f * L;
      if (d >= min_span || d < 1e-6f) continue;
      glm::vec3 fix = delta * ((d - min_span) / d);
      if (k == 0) {
        joints_[2] -= fix;
      } else {
        joints_[k] += 0.5f * fix;
        joints_[k + 2] -= 0.5f * fix;
      }
    }
    for (int k = 1; k < kJoints; ++k) joints_[k].y = std::max(joints_[k].y, floor_y);
  }
  // Friction: a joint pressed into the paper loses its sliding velocity (it drags behind).
  for (int k = 1; k < kJoints; ++k)
    if (joints_[k].y <= 0.0f) {
      previous_[k].x = joints_[k].x;
      previous_[k].z = joints_[k].z;
    }
  ++steps_;
}

FootprintRect SkeletonBrush::stampBristles(float pressure, Footprint* fp) {
  float dispersion = dispersionForSpeed(dispersion_params_, speed_px_s_);
  float W = params_.bristle_spread_px, splay = params_.bristle_splay * pressure;
  const glm::vec3* J = joints_.data();
  FootprintRect changed;
  int points = params_.bristle_points;
  for (const Bristle& b : bristles_) {
    glm::vec3 o(b.offset.x, 0.0f, b.offset.y);
    glm::vec3 p0 = J[0] + o * (0.6f * W);
    glm::vec3 p1 = J[1] + o * W;
    glm::vec3 p2 = J[2] + o * (W * (1.0f + 0.5f * splay));
    glm::vec3 p3 = J[2] + (J[3] - J[2]) * b.length + o * (W * (0.4f + splay));
    for (int m = 0; m < points; ++m) {
      glm::vec3 q = cubicBezier(p0, p1, p2, p3, float(m) / float(points - 1));
      if (q.y >= 0.0f) continue;  // above the paper: no ink
      float ink = std::min(1.0f, -q.y / params_.paper_softness_px);
      changed = changed.united(
          splatDot(glm::vec2(q.x, q.z), params_.bristle_radius_px, ink, dispersion, field_, fp));
    }
  }
  return changed;
}

}  // namespace cb
