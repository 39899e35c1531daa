#include "app/scene/paint_camera.h"

#include <algorithm>
#include <cmath>

#include "app/scene/drawable_region.h"

namespace cb {
namespace {

// Unit vector from the target towards the eye at a yaw and elevation.
glm::vec3 eyeDirection(float yaw_deg, float elevation_deg) {
  const float yaw = glm::radians(yaw_deg), elevation = glm::radians(elevation_deg);
  return {std::sin(yaw) * std::cos(elevation), std::sin(elevation),
          std::cos(yaw) * std::cos(elevation)};
}

// Yaw of a camera's view (the framing's convention), from its eye's offset to its target.
float yawDeg(const Camera& c) {
  const glm::vec3 back = c.eye - c.target;
  return glm::degrees(std::atan2(back.x, back.z));
}

}  // namespace

Camera framePaintCamera(const Canvas& canvas, glm::vec3 box_min, glm::vec3 box_max, float aspect,
                        const PaintFraming& framing) {
  Camera c;
  c.fov_y_deg = framing.fov_y_deg;
  const glm::vec3 f = -eyeDirection(framing.yaw_deg, framing.elevation_deg);
  const glm::vec3 r = glm::normalize(glm::cross(f, c.up)), u = glm::cross(r, f);
  const float fit = 1.0f - framing.margin;
  const float ky = fit * std::tan(glm::radians(framing.fov_y_deg) * 0.5f), kx = ky * aspect;
  // A point p with camera coordinates (a, b, c) = (p·r, p·u, p·f) is inside the inset screen
  // when |a − e_r| <= kx·(c − e_f) and |b − e_u| <= ky·(c − e_f), e = the eye's coordinates.
  // For the corners, the two horizontal bounds give e_r − kx·e_f >= max(a − kx·c) =: A_h and
  // e_r + kx·e_f <= min(a + kx·c) =: B_h; both tight at e_f = (B_h − A_h) / (2·kx). The same
  // vertically; the eye takes the smaller e_f (further back) and the middle of the slack.
  // Horizontal bounds: the rectangle clipped to the depth of side_fit_depth (its nearer part
  // may spill past the screen's sides); vertical bounds: the whole rectangle.
  const glm::vec3 corners[4] = {{box_min.x, canvas.altitude, box_min.z},
                                {box_max.x, canvas.altitude, box_min.z},
                                {box_max.x, canvas.altitude, box_max.z},
                                {box_min.x, canvas.altitude, box_max.z}};
  float c_far = -INFINITY, c_near = INFINITY;
  for (const glm::vec3& p : corners) {
    c_far = std::max(c_far, glm::dot(p, f));
    c_near = std::min(c_near, glm::dot(p, f));
  }
  const float c_cut = c_far + std::clamp(framing.side_fit_depth, 0.0f, 1.0f) * (c_near - c_far);
  float a_h = -INFINITY, b_h = INFINITY, a_v = -INFINITY, b_v = INFINITY;
  const auto boundHorizontally = [&](glm::vec3 p) {
    const float pa = glm::dot(p, r), pc = glm::dot(p, f);
    a_h = std::max(a_h, pa - kx * pc);
    b_h = std::min(b_h, pa + kx * pc);
  };
  for (int i = 0; i < 4; ++i) {
    const glm::vec3 p = corners[i], q = corners[(i + 1) % 4];
    const float pb = glm::dot(p, u), pc = glm::dot(p, f), qc = glm::dot(q, f);
    a_v = std::max(a_v, pb - ky * pc);
    b_v = std::min(b_v, pb + ky * pc);
    if (pc >= c_cut) boundHorizontally(p);
    if ((pc >= c_cut) != (qc >= c_cut)) boundHorizontally(p + (q - p) * ((pc - c_cut) / (pc - qc)));
  }
  const float e_f = std::min((b_h - a_h) / (2.0f * kx), (b_v - a_v) / (2.0f * ky));
  c.eye = 0.5f * (a_h + b_h) * r + 0.5f * (a_v + b_v) * u + e_f * f;
  // Target: where the view axis meets the canvas mid-plane (f.y < 0 for elevation > 0).
  const float t = f.y < -1e-6f ? (canvas.altitude - c.eye.y) / f.y : 1.0f;
  c.target = c.eye + f * t;
  return c;
}

Camera defaultPaintCamera(const Canvas& canvas, glm::vec3 box_min, glm::vec3 box_max,
                          float aspect) {
  return framePaintCamera(canvas, box_min, box_max, aspect, PaintFraming{});
}

float viewElevationDeg(const Camera& camera) {
  const glm::vec3 f = glm::normalize(camera.target - camera.eye);
  return glm::degrees(std::asin(std::clamp(-f.y, -1.0f, 1.0f)));
}

Camera withElevation(const Camera& camera, float elevation_deg) {
  Camera c = camera;
  const float distance = glm::length(camera.eye - camera.target);
  c.eye = camera.target + distance * eyeDirection(yawDeg(camera), elevation_deg);
  return c;
}

PaintViewAssessment assessPaintView(const Camera& camera, const Canvas& canvas, glm::vec3 box_min,
                                    glm::vec3 box_max, int width, int height,
                                    const GoodViewCriteria& criteria) {
  PaintViewAssessment a;
  a.elevation_deg = viewElevationDeg(camera);
  a.fill_fraction = DrawableRegion(camera, canvas, box_min, box_max, width, height).fillFraction();
  a.edge_on = a.elevation_deg < criteria.min_elevation_deg;
  a.good = !a.edge_on && a.fill_fraction >= criteria.min_fill_fraction;
  return a;
}

Camera nearestGoodPaintView(const Camera& camera, const Canvas& canvas, glm::vec3 box_min,
                            glm::vec3 box_max, int width, int height,
                            const GoodViewCriteria& criteria) {
  if (assessPaintView(camera, canvas, box_min, box_max, width, height, criteria).good)
    return camera;
  const float start = viewElevationDeg(camera);
  const float step = std::max(criteria.elevation_step_deg, 0.01f);
  Camera best = camera;
  double best_fill = -1.0;
  for (int k = 1;; ++k) {
    const float elevation = std::min(start + float(k) * step, criteria.max_elevation_deg);
    const Camera c = withElevation(camera, elevation);
    const PaintViewAssessment a =
        assessPaintView(c, canvas, box_min, box_max, width, height, criteria);
    if (a.good) return c;
    if (!a.edge_on && a.fill_fraction > best_fill) best = c, best_fill = a.fill_fraction;
    if (elevation >= criteria.max_elevation_deg) break;
  }
  return best_fill >= 0.0 ? best : withElevation(camera, criteria.max_elevation_deg);
}

}  // namespace cb
