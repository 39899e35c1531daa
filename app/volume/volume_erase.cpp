#include "app/volume/volume_erase.h"

#include <algorithm>
#include <cmath>

namespace cb {
namespace {

float smoothstep(float e0, float e1, float x) {
  if (e1 <= e0) return x < e0 ? 0.0f : 1.0f;
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// Voxels whose centres may lie within [lo, hi] (world), clipped to the volume.
VoxelBox voxelBoxOf(const Volume& volume, glm::vec3 lo, glm::vec3 hi) {
  const glm::vec3 a = volume.worldToVoxel(lo), b = volume.worldToVoxel(hi);
  VoxelBox box{glm::ivec3(glm::floor(glm::min(a, b))) - 1,
               glm::ivec3(glm::ceil(glm::max(a, b))) + 1};
  return box.intersect(volume.bounds());
}

// Multiplies each voxel of `box` by keep(world centre) and marks what changed.
template <typename Keep>
VoxelBox scaleDensity(Volume& volume, const VoxelBox& box, Keep&& keep) {
  VoxelBox changed;
  for (int z = box.lo.z; z < box.hi.z; ++z)
    for (int y = box.lo.y; y < box.hi.y; ++y)
      for (int x = box.lo.x; x < box.hi.x; ++x) {
        const float d = volume.at(x, y, z);
        if (d == 0.0f) continue;
        const float k = keep(volume.voxelToWorld(glm::vec3(x, y, z) + 0.5f));
        if (k >= 1.0f) continue;
        volume.voxelForWrite(x, y, z) = d * k;
        changed = changed.unite({{x, y, z}, {x + 1, y + 1, z + 1}});
      }
  if (changed.empty()) return changed;
  volume.markDirty(changed);
  // Bricks the erase emptied give their memory back (they read zero either way).
  const glm::ivec3 lo = changed.lo >> Volume::kBrickShift,
                   hi = (changed.hi - 1) >> Volume::kBrickShift;
  for (int bz = lo.z; bz <= hi.z; ++bz)
    for (int by = lo.y; by <= hi.y; ++by)
      for (int bx = lo.x; bx <= hi.x; ++bx) volume.releaseEmptyBrick({bx, by, bz});
  return changed;
}

bool finite(glm::vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

VoxelBox vacuumSphere(Volume& volume, glm::vec3 centre, float radius, float soft) {
  if (!(radius > 0.0f) || !std::isfinite(radius) || !finite(centre)) return {};
  const VoxelBox box = voxelBoxOf(volume, centre - radius, centre + radius);
  const float inner = radius * (1.0f - std::clamp(soft, 0.0f, 1.0f));
  return scaleDensity(
      volume, box, [&](glm::vec3 p) { return smoothstep(inner, radius, glm::length(p - centre)); });
}

VoxelBox rubOutCylinder(Volume& volume, glm::vec3 origin, glm::vec3 dir, float radius, float y_min,
                        float y_max) {
  if (!(radius > 0.0f) || !finite(origin) || !finite(dir) || glm::length(dir) < 1e-6f ||
      !(y_max > y_min))
    return {};
  dir = glm::normalize(dir);
  // The part of the ray inside the height range (and in front of the origin), widened by the
  // radius, bounds the voxels to visit.
  float t0 = 0.0f, t1 = 0.0f;
  if (std::abs(dir.y) > 1e-6f) {
    const float ta = (y_min - origin.y) / dir.y, tb = (y_max - origin.y) / dir.y;
    t0 = std::max(0.0f, std::min(ta, tb));
    t1 = std::max(ta, tb);
  } else if (origin.y >= y_min && origin.y <= y_max) {
    t1 = 2.0f * glm::length(volume.worldMax() - volume.worldMin()) + glm::length(origin);
  }
  if (t1 <= t0) return {};
  const glm::vec3 a = origin + t0 * dir, b = origin + t1 * dir;
  glm::vec3 lo = glm::min(a, b) - radius, hi = glm::max(a, b) + radius;
  lo.y = std::max(lo.y, y_min);
  hi.y = std::min(hi.y, y_max);
  const VoxelBox box = voxelBoxOf(volume, lo, hi);
  const float rim = glm::length(volume.voxelSize()) / std::sqrt(3.0f);  // one voxel
  return scaleDensity(volume, box, [&](glm::vec3 p) {
    if (p.y < y_min || p.y > y_max) return 1.0f;
    const float along = glm::dot(p - origin, dir);
    if (along < 0.0f) return 1.0f;
    const float off_axis = glm::length(p - (origin + along * dir));
    return smoothstep(radius - rim, radius, off_axis);
  });
}

}  // namespace cb
