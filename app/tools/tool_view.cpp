#include "app/tools/tool_view.h"

#include <algorithm>

namespace cb {

glm::vec3 toolAnchor(const ToolView& view, const Volume& volume) {
  PaintViewGeometry geometry(view.camera, view.view_width, view.view_height);
  glm::vec3 origin, dir;
  geometry.ray(0.5f * view.view_width - 0.5f, 0.5f * view.view_height - 0.5f, &origin, &dir);
  const glm::vec3 centre = 0.5f * (volume.worldMin() + volume.worldMax());
  const glm::vec3 fallback(centre.x, view.canvas.altitude, centre.z);
  const float max_distance = 4.0f * glm::length(volume.worldMax() - volume.worldMin()) +
                             glm::length(view.camera.eye - centre);
  glm::vec3 point;
  geometry.placeOnCanvas(view.canvas, origin, dir, fallback, max_distance, &point);
  return point;
}

PicturePlacement::PicturePlacement(const ToolView& view, const Volume& volume, int picture_width,
                                   int picture_height)
    : geometry_(view.camera, view.view_width, view.view_height) {
  anchor_ = toolAnchor(view, volume);
  anchor_depth_ = geometry_.depthOf(anchor_);
  scale_ = view.size_fraction * std::min(float(view.view_width) / float(picture_width),
                                         float(view.view_height) / float(picture_height));
  origin_ = 0.5f * glm::vec2(view.view_width, view.view_height) -
            0.5f * scale_ * glm::vec2(picture_width, picture_height);
}

float PicturePlacement::pictureTexelWorldSize() const {
  return geometry_.pixelWorldSize(anchor_depth_) * scale_;
}

glm::vec3 PicturePlacement::worldPoint(glm::vec2 picture, float depth_offset) const {
  const glm::vec2 v = toView(picture);
  glm::vec3 origin, dir;
  geometry_.ray(v.x - 0.5f, v.y - 0.5f, &origin, &dir);
  const float along = glm::dot(dir, geometry_.forward());
  const float t = (glm::dot(anchor_ - origin, geometry_.forward()) + depth_offset) / along;
  return origin + dir * t;
}

}  // namespace cb
