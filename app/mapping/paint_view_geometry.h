// The paint view as the mapping needs it: pixel rays of a footprint (the same rays as
// Camera::pixelRay, with the inverse matrix computed once), world size of a pixel at a depth,
// and where a ray meets the 3D canvas.
#pragma once

#include <glm/glm.hpp>

#include "app/scene/camera.h"
#include "app/scene/canvas.h"

namespace cb {

class PaintViewGeometry {
 public:
  PaintViewGeometry(const Camera& camera, int width, int height);

  // Ray through the centre of footprint pixel (px, py); origin on the near plane.
  void ray(float px, float py, glm::vec3* origin, glm::vec3* dir) const;
  // Distance of p in front of the eye, along the view axis.
  float depthOf(glm::vec3 p) const { return glm::dot(p - eye_, forward_); }
  // World length of one footprint pixel at that depth (perspective: 2·d·tan(fov/2) / height).
  float pixelWorldSize(float depth) const { return depth * pixel_size_per_depth_; }

  glm::vec3 eye() const { return eye_; }
  glm::vec3 forward() const { return forward_; }
  glm::vec3 right() const { return right_; }
  glm::vec3 up() const { return up_; }
  // True when the view axis is within `degrees` of the canvas plane (rays graze it).
  bool nearlyParallelToCanvas(float degrees = 3.0f) const;

  // Where the ray meets the canvas mid-plane (§6.5). When it does not (parallel, behind, or
  // beyond `max_distance`), falls back to the plane facing the camera through `fallback_point`
  // and returns false.
  bool placeOnCanvas(const Canvas& canvas, glm::vec3 origin, glm::vec3 dir,
                     glm::vec3 fallback_point, float max_distance, glm::vec3* point) const;

 private:
  glm::mat4 inverse_view_projection_;
  int width_, height_;
  glm::vec3 eye_, forward_, right_, up_;
  float pixel_size_per_depth_;
};

}  // namespace cb
