#include "app/mapping/stroke_reach.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "app/mapping/paint_view_geometry.h"
#include "app/mapping/sphere_mapping.h"

namespace cb {

SkyReach strokeReach(const StrokeResult& stroke, const MappingConfig& config, float voxel_size) {
  SkyReach reach;
  const Footprint& f = stroke.footprint;
  if (f.width <= 0 || f.height <= 0 || f.values.size() != size_t(f.width) * size_t(f.height))
    return reach;
  // The inked pixels' bounding rectangle (NaN is empty, +inf ink: as StrokeMapper::map).
  const float empty = config.circles.empty_threshold;
  int x0 = f.width, y0 = f.height, x1 = -1, y1 = -1;
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x)
      if (f.at(x, y) > empty) {
        x0 = std::min(x0, x);
        x1 = std::max(x1, x);
        y0 = std::min(y0, y);
        y1 = std::max(y1, y);
      }
  if (x1 < 0) return reach;
  reach.inked = true;

  const PaintViewGeometry view(stroke.view.camera, f.width, f.height);
  const Canvas& canvas = stroke.canvas;
  const glm::vec3 eye = view.eye();
  // The rectangle's outer pixel edges (ray() goes through a pixel's centre).
  const glm::vec2 corners[4] = {{float(x0) - 0.5f, float(y0) - 0.5f},
                                {float(x1) + 0.5f, float(y0) - 0.5f},
                                {float(x0) - 0.5f, float(y1) + 0.5f},
                                {float(x1) + 0.5f, float(y1) + 0.5f}};
  glm::vec3 origin[4], dir[4];
  float d_min = std::numeric_limits<float>::infinity(), d_max = 0.0f;
  const bool eye_in_slab = eye.y >= canvas.bottom() && eye.y <= canvas.top();
  for (int c = 0; c < 4; ++c) {
    view.ray(corners[c].x, corners[c].y, &origin[c], &dir[c]);
    float t_mid = 0.0f;
    if (!canvas.intersectMidPlane(origin[c], dir[c], &t_mid)) return reach;  // not bounded
    const float along = glm::dot(dir[c], view.forward());
    if (!(along > 1e-6f)) return reach;
    for (const float plane : {canvas.bottom(), canvas.altitude, canvas.top()}) {
      if (std::abs(dir[c].y) < 1e-6f) continue;
      const float t = (plane - origin[c].y) / dir[c].y;
      if (t <= 0.0f) continue;
      const float d = view.depthOf(origin[c] + t * dir[c]);
      d_min = std::min(d_min, d);
      d_max = std::max(d_max, d);
    }
    if (eye_in_slab) d_min = std::min(d_min, view.depthOf(origin[c]));
  }
  // The largest sphere: circles start at the initial diameter and shrink (§6.3.3); an accepted
  // circle is at least a fraction a (accept_white_ratio) white, white pixels lie in the inked
  // rectangle, and a circle of radius r meets a strip m wide (the rectangle's narrower side) in
  // less than 2·r·m pixels: so a·π·r² < 2·r·m, r < 2m / (π·a).
  const float m = float(std::min(x1 - x0, y1 - y0) + 1);
  const float a = config.circles.accept_white_ratio;
  const float r_px = std::min(0.5f * float(config.circles.initial_diameter_px),
                              a > 0.0f ? 2.0f * m / (3.14159265f * a) : 1e30f);
  // Billows (billows.h) swell a sphere by up to 1 + billow_amplitude.
  const float r_world =
      sphereFillRadius(r_px * (1.0f + config.spheres.billow_amplitude) * view.pixelWorldSize(d_max),
                       voxel_size, config.spheres);
  const float margin = 2.0f * r_world + 8.0f * voxel_size;
  const float near = std::max(d_min - margin, 0.0f), far = d_max + margin;
  reach.xz_min = glm::vec2(std::numeric_limits<float>::infinity());
  reach.xz_max = -reach.xz_min;
  for (int c = 0; c < 4; ++c) {
    const float along = glm::dot(dir[c], view.forward());
    const float d0 = view.depthOf(origin[c]);
    for (const float d : {near, far}) {
      const glm::vec3 p = origin[c] + dir[c] * (std::max(d - d0, 0.0f) / along);
      reach.xz_min = glm::min(reach.xz_min, glm::vec2(p.x, p.z));
      reach.xz_max = glm::max(reach.xz_max, glm::vec2(p.x, p.z));
    }
  }
  reach.xz_min -= margin;
  reach.xz_max += margin;
  reach.bounded = std::isfinite(reach.xz_min.x) && std::isfinite(reach.xz_min.y) &&
                  std::isfinite(reach.xz_max.x) && std::isfinite(reach.xz_max.y);
  return reach;
}

}  // namespace cb
