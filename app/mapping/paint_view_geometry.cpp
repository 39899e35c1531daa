#include "app/mapping/paint_view_geometry.h"

#include <cmath>

namespace cb {

PaintViewGeometry::PaintViewGeometry(const Camera& camera, int width, int height)
    : width_(width), height_(height) {
  inverse_view_projection_ =
      glm::inverse(camera.projection(float(width) / float(height)) * camera.view());
  eye_ = camera.eye;
  forward_ = glm::normalize(camera.target - camera.eye);
  right_ = glm::normalize(glm::cross(forward_, camera.up));
  up_ = glm::cross(right_, forward_);
  pixel_size_per_depth_ =
      2.0f * std::tan(glm::radians(camera.fov_y_deg) * 0.5f) / float(height > 0 ? height : 1);
}

void PaintViewGeometry::ray(float px, float py, glm::vec3* origin, glm::vec3* dir) const {
  // Same arithmetic as Camera::pixelRay.
  float ndc_x = 2.0f * (px + 0.5f) / float(width_) - 1.0f;
  float ndc_y = 1.0f - 2.0f * (py + 0.5f) / float(height_);
  glm::vec4 n = inverse_view_projection_ * glm::vec4(ndc_x, ndc_y, -1.0f, 1.0f);
  glm::vec4 f = inverse_view_projection_ * glm::vec4(ndc_x, ndc_y, 1.0f, 1.0f);
  glm::vec3 near_point = glm::vec3(n) / n.w;
  glm::vec3 far_point = glm::vec3(f) / f.w;
  *origin = near_point;
  *dir = glm::normalize(far_point - near_point);
}

bool PaintViewGeometry::nearlyParallelToCanvas(float degrees) const {
  return std::abs(forward_.y) < std::sin(glm::radians(degrees));
}

bool PaintViewGeometry::placeOnCanvas(const Canvas& canvas, glm::vec3 origin, glm::vec3 dir,
                                      glm::vec3 fallback_point, float max_distance,
                                      glm::vec3* point) const {
  float t;
  if (canvas.intersectMidPlane(origin, dir, &t) && t <= max_distance) {
    *point = origin + dir * t;
    return true;
  }
  // Plane through fallback_point facing the camera.
  float denom = glm::dot(dir, forward_);
  float s = denom > 1e-6f ? glm::dot(fallback_point - origin, forward_) / denom : 0.0f;
  *point = origin + dir * std::max(s, 0.0f);
  return false;
}

}  // namespace cb
