// A perspective camera in world space (y up). Shared by the renderer, the paint view of the
// brushes and the mapping, so all three agree on what a pixel means.
#pragma once

#include <glm/glm.hpp>

namespace cb {

struct Camera {
  glm::vec3 eye{2.2f, 1.6f, 2.2f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fov_y_deg = 45.0f;
  float near_plane = 0.01f;
  float far_plane = 100.0f;

  glm::mat4 view() const;
  glm::mat4 projection(float aspect) const;
  // World-space ray through pixel centre (px, py) of a width×height image, py = 0 at the top.
  // The origin lies on the near plane, so rays start correctly when the eye is inside a volume.
  void pixelRay(float px, float py, int width, int height, glm::vec3* origin, glm::vec3* dir) const;

  // The fixed reference camera of tests and benchmarks: a 3/4 view of the unit sky box
  // [-1,1]^3 from above and to the side, 45° vertical field of view.
  static Camera reference();
  // The same camera rotated about the y axis through `target` by `degrees`.
  Camera orbited(float degrees) const;
  // The same camera moved in its view plane (eye and target together) by `right` and `up`
  // world units along the screen's right and up directions: a pan.
  Camera panned(float right, float up) const;
  // The eye moved along the view direction to `factor` times its distance from the target
  // (< 1 closer); the distance stays within [0.05, 50] world units.
  Camera zoomed(float factor) const;
  // World units per screen pixel at the target's distance, on an image `height` pixels high:
  // a drag of n pixels pans the point under the pen by n × this.
  float worldPerPixelAtTarget(int height) const;
};

}  // namespace cb
