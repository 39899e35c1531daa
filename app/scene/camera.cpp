#include "app/scene/camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace cb {

glm::mat4 Camera::view() const {
  return glm::lookAt(eye, target, up);
}

glm::mat4 Camera::projection(float aspect) const {
  return glm::perspective(glm::radians(fov_y_deg), aspect, near_plane, far_plane);
}

void Camera::pixelRay(float px, float py, int width, int height, glm::vec3* origin,
                      glm::vec3* dir) const {
  glm::mat4 inv = glm::inverse(projection(float(width) / float(height)) * view());
  float ndc_x = 2.0f * (px + 0.5f) / float(width) - 1.0f;
  float ndc_y = 1.0f - 2.0f * (py + 0.5f) / float(height);
  glm::vec4 n = inv * glm::vec4(ndc_x, ndc_y, -1.0f, 1.0f);
  glm::vec4 f = inv * glm::vec4(ndc_x, ndc_y, 1.0f, 1.0f);
  glm::vec3 near_point = glm::vec3(n) / n.w;
  glm::vec3 far_point = glm::vec3(f) / f.w;
  *origin = near_point;
  *dir = glm::normalize(far_point - near_point);
}

Camera Camera::reference() {
  Camera c;
  c.eye = glm::vec3(2.3f, 1.5f, 2.3f);
  c.target = glm::vec3(0.0f, -0.05f, 0.0f);
  c.fov_y_deg = 45.0f;
  return c;
}

Camera Camera::orbited(float degrees) const {
  Camera c = *this;
  glm::mat4 r = glm::rotate(glm::mat4(1.0f), glm::radians(degrees), up);
  c.eye = target + glm::vec3(r * glm::vec4(eye - target, 0.0f));
  return c;
}

Camera Camera::panned(float right, float up_amount) const {
  const glm::vec3 forward = glm::normalize(target - eye);
  const glm::vec3 screen_right = glm::normalize(glm::cross(forward, up));
  const glm::vec3 screen_up = glm::cross(screen_right, forward);
  const glm::vec3 shift = right * screen_right + up_amount * screen_up;
  Camera c = *this;
  c.eye += shift;
  c.target += shift;
  return c;
}

Camera Camera::zoomed(float factor) const {
  const glm::vec3 offset = eye - target;
  const float distance = glm::length(offset);
  Camera c = *this;
  c.eye = target + offset * (glm::clamp(distance * factor, 0.05f, 50.0f) / distance);
  return c;
}

float Camera::worldPerPixelAtTarget(int height) const {
  const float distance = glm::length(eye - target);
  return 2.0f * distance * std::tan(glm::radians(fov_y_deg) * 0.5f) / float(std::max(height, 1));
}

}  // namespace cb
