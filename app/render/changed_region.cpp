#include "app/render/changed_region.h"

#include <algorithm>
#include <climits>
#include <cmath>

namespace cb {

ScreenRegion ScreenRegion::unite(const ScreenRegion& o) const {
  if (empty()) return o;
  if (o.empty()) return *this;
  const glm::ivec2 lo = glm::min(glm::ivec2(rect.x, rect.y), glm::ivec2(o.rect.x, o.rect.y));
  const glm::ivec2 hi = glm::max(glm::ivec2(rect.x + rect.z, rect.y + rect.w),
                                 glm::ivec2(o.rect.x + o.rect.z, o.rect.y + o.rect.w));
  return {glm::ivec4(lo, hi - lo), whole_frame || o.whole_frame};
}

float readReachVoxels(RenderStyle style, glm::ivec3 dims) {
  // One voxel of trilinear footprint, one more for rounding of sample positions.
  float reach = 2.0f;
  // The iso-surface normal reads u_gradient_voxels away from the hit (volume_renderer.cpp:
  // max(1, largest dim / 64)).
  if (drawsIsoSurface(style))
    reach += std::max(1.0f, float(std::max({dims.x, dims.y, dims.z})) / 64.0f);
  return reach;
}

ScreenRegion projectVoxelBoxes(const Camera& camera, int width, int height, const Volume& volume,
                               const std::vector<VoxelBox>& boxes, float reach_voxels) {
  const glm::mat4 view_proj = camera.projection(float(width) / float(height)) * camera.view();
  glm::vec2 lo(1e30f), hi(-1e30f);
  bool any = false;
  for (const VoxelBox& box : boxes) {
    if (box.empty()) continue;
    any = true;
    const glm::vec3 wlo = volume.voxelToWorld(glm::vec3(box.lo) - reach_voxels);
    const glm::vec3 whi = volume.voxelToWorld(glm::vec3(box.hi) + reach_voxels);
    if (glm::all(glm::greaterThanEqual(camera.eye, wlo)) &&
        glm::all(glm::lessThanEqual(camera.eye, whi)))
      return ScreenRegion::wholeFrame(width, height);
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec3 p((corner & 1) ? whi.x : wlo.x, (corner & 2) ? whi.y : wlo.y,
                        (corner & 4) ? whi.z : wlo.z);
      const glm::vec4 clip = view_proj * glm::vec4(p, 1.0f);
      // A corner on or behind the near plane: the box's projection is unbounded there.
      if (clip.w <= camera.near_plane) return ScreenRegion::wholeFrame(width, height);
      const glm::vec2 ndc = glm::vec2(clip) / clip.w;
      const glm::vec2 px = (ndc * 0.5f + 0.5f) * glm::vec2(float(width), float(height));
      lo = glm::min(lo, px);
      hi = glm::max(hi, px);
    }
  }
  if (!any) return {};
  // Pixel centres inside the projected hull lie in these pixels; one more pixel each side for
  // rasterisation rounding.
  const glm::ivec2 a = glm::max(glm::ivec2(glm::floor(lo)) - 1, glm::ivec2(0));
  const glm::ivec2 b = glm::min(glm::ivec2(glm::ceil(hi)) + 1, glm::ivec2(width, height));
  if (b.x <= a.x || b.y <= a.y) return {};  // entirely off screen
  ScreenRegion region{glm::ivec4(a, b - a), false};
  if (region.rect == glm::ivec4(0, 0, width, height)) region.whole_frame = true;
  return region;
}

VoxelBox occupiedPartOf(const OccupancyPyramid& occupancy, const VoxelBox& box) {
  if (box.empty() || occupancy.levels.empty()) return box;
  const int brick = occupancy.brick;
  const glm::ivec3 d = occupancy.level_dims[0];
  const glm::ivec3 c0 = glm::max(box.lo / brick, glm::ivec3(0));
  const glm::ivec3 c1 = glm::min((box.hi + brick - 1) / brick, d);
  const std::vector<uint8_t>& cells = occupancy.levels[0];
  glm::ivec3 lo(INT32_MAX), hi(INT32_MIN);
  for (int z = c0.z; z < c1.z; ++z)
    for (int y = c0.y; y < c1.y; ++y)
      for (int x = c0.x; x < c1.x; ++x)
        if (cells[(size_t(z) * size_t(d.y) + size_t(y)) * size_t(d.x) + size_t(x)]) {
          lo = glm::min(lo, glm::ivec3(x, y, z));
          hi = glm::max(hi, glm::ivec3(x, y, z) + 1);
        }
  if (lo.x > hi.x) return {};
  return box.intersect({lo * brick, hi * brick});
}

ScreenRegion changedScreenRegion(const Camera& camera, int width, int height, const Volume& volume,
                                 const SyncStats& sync, const OccupancyPyramid& occupancy,
                                 RenderStyle style) {
  // The light box is swept in float, but the GPU reads 8-bit transmittance: only the slots
  // whose bytes changed (sync.changed_slots) can change a pixel, and within the light box that
  // is often far less (deep in the cloud's shadow the 8-bit value stays where it was).
  return projectVoxelBoxes(
      camera, width, height, volume,
      {sync.dirty, occupiedPartOf(occupancy, sync.light_box.intersect(sync.changed_slots))},
      readReachVoxels(style, volume.dims()));
}

}  // namespace cb
