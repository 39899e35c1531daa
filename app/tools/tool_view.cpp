#include "app/tools/tool_view.h"

#include <algorithm>
#include <cmath>

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

SkyReach placementReach(const VoxelBox& voxels, const Volume& volume) {
  SkyReach reach;
  reach.inked = !voxels.empty();
  if (!reach.inked) return reach;
  const glm::vec3 lo = volume.voxelToWorld(glm::vec3(voxels.lo));
  const glm::vec3 hi = volume.voxelToWorld(glm::vec3(voxels.hi));
  reach.xz_min = glm::vec2(lo.x, lo.z);
  reach.xz_max = glm::vec2(hi.x, hi.z);
  reach.bounded =
      std::isfinite(lo.x) && std::isfinite(lo.z) && std::isfinite(hi.x) && std::isfinite(hi.z);
  return reach;
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
