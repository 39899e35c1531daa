#include "app/render/changed_region.h"

#include <algorithm>
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

float readReachVoxels(RenderStyle style, glm::vec3 voxel_size) {
  // One voxel of trilinear footprint, one more for rounding of sample positions.
  float reach = 2.0f;
  // The iso-surface normal reads isoSurfaceReach's gradient_voxels away from the hit.
  if (drawsIsoSurface(style)) reach += isoSurfaceReach(voxel_size).gradient_voxels;
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

VoxelBox visibleChange(const BrickPool::SlotChange& change, RenderStyle style) {
  return drawsIsoSurface(style) ? change.bytes : change.weighted;
}

std::vector<VoxelBox> visibleChanges(const std::vector<BrickPool::SlotChange>& changes,
                                     RenderStyle style) {
  std::vector<VoxelBox> boxes;
  boxes.reserve(changes.size());
  for (const BrickPool::SlotChange& change : changes) {
    const VoxelBox box = visibleChange(change, style);
    if (!box.empty()) boxes.push_back(box);
  }
  return boxes;
}

ScreenRegion changedScreenRegion(const Camera& camera, int width, int height, const Volume& volume,
                                 const SyncStats& sync, RenderStyle style) {
  if (sync.light_moved) return ScreenRegion::wholeFrame(width, height);
  return projectVoxelBoxes(camera, width, height, volume, visibleChanges(sync.changes, style),
                           readReachVoxels(style, volume.voxelSize()));
}

}  // namespace cb
