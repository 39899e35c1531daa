#include "app/mapping/ray_marching_mapping.h"

#include <algorithm>
#include <cmath>

#include "app/core/parallel_for.h"

namespace cb {
namespace {

struct Segment {
  glm::vec3 start;  // world point of the first sample's interval
  glm::vec3 dir;
  int samples;
};

// Clips the ray parameter interval [*t0, *t1] to an axis-aligned box; false if empty.
bool clipToBox(glm::vec3 o, glm::vec3 d, glm::vec3 lo, glm::vec3 hi, float* t0, float* t1) {
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-12f) {
      if (o[a] < lo[a] || o[a] > hi[a]) return false;
      continue;
    }
    float ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    *t0 = std::max(*t0, ta);
    *t1 = std::min(*t1, tb);
  }
  return *t0 < *t1;
}

}  // namespace

VoxelBox mapRayMarching(const Footprint& f, const PaintViewGeometry& view, const Canvas& canvas,
                        const RayMarchingConfig& cfg, float empty_threshold, Volume& volume,
                        RayMarchingStats* stats) {
  RayMarchingStats local;
  const glm::vec3 vs = volume.voxelSize();
  const float step = 0.5f * std::min({vs.x, vs.y, vs.z});

  // Segments, one per non-empty pixel, in row order.
  std::vector<Segment> segments;
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) {
      const float value = std::min(1.0f, f.at(x, y));
      if (!(value > empty_threshold)) continue;
      ++local.pixels;
      glm::vec3 o, d;
      view.ray(float(x), float(y), &o, &d);
      if (std::abs(d.y) < 1e-6f) {
        ++local.parallel_pixels;
        continue;
      }
      float t_floor = (canvas.bottom() - o.y) / d.y, t_ceiling = (canvas.top() - o.y) / d.y;
      float t_near = std::min(t_floor, t_ceiling), t_far = std::max(t_floor, t_ceiling);
      float t_mid = 0.5f * (t_near + t_far);  // B, on the mid-plane
      if (t_far <= 0.0f) {
        ++local.parallel_pixels;
        continue;
      }
      // Grow from B by value·|B i1| towards the near face and value·|B i2| towards the far one.
      float t0 = std::max(0.0f, t_mid - value * (t_mid - t_near));
      float t1 = t_mid + value * (t_far - t_mid);
      if (!clipToBox(o, d, volume.worldMin(), volume.worldMax(), &t0, &t1)) continue;
      ++local.mapped_pixels;
      segments.push_back({o + d * t0, d, std::max(1, int(std::ceil((t1 - t0) / step)))});
    }

  // Voxel box of all segments.
  VoxelBox all;
  for (const Segment& s : segments) {
    glm::vec3 a = volume.worldToVoxel(s.start);
    glm::vec3 b = volume.worldToVoxel(s.start + s.dir * (step * float(s.samples)));
    all = all.unite(
        {glm::ivec3(glm::floor(glm::min(a, b))), glm::ivec3(glm::floor(glm::max(a, b))) + 1});
  }
  all = all.intersect(volume.bounds());
  if (all.empty()) {
    if (stats) *stats = local;
    return {};
  }

  // Fill by z slabs: each chunk writes only voxels with z in its slab. Sample positions are
  // global (start + (i + 0.5)·step), so the result is independent of the chunking.
  constexpr size_t kSlab = 4;
  const glm::ivec3 dims = volume.dims();
  const float density = cfg.density;
  parallelFor(size_t(all.hi.z - all.lo.z), kSlab, [&](size_t, size_t k0, size_t k1) {
    const int z0 = all.lo.z + int(k0), z1 = all.lo.z + int(k1);
    const float wz0 = volume.worldMin().z + float(z0) * vs.z;
    const float wz1 = volume.worldMin().z + float(z1) * vs.z;
    for (const Segment& s : segments) {
      int i0 = 0, i1 = s.samples;
      if (std::abs(s.dir.z) > 1e-9f) {
        // Samples whose z lies in [wz0, wz1), widened by one sample on each side.
        float ta = (wz0 - s.start.z) / s.dir.z, tb = (wz1 - s.start.z) / s.dir.z;
        if (ta > tb) std::swap(ta, tb);
        i0 = std::max(i0, int(std::floor(ta / step - 0.5f)) - 1);
        i1 = std::min(i1, int(std::ceil(tb / step - 0.5f)) + 2);
      } else if (s.start.z < wz0 || s.start.z >= wz1) {
        continue;
      }
      for (int i = i0; i < i1; ++i) {
        glm::vec3 p = s.start + s.dir * (step * (float(i) + 0.5f));
        glm::ivec3 v(glm::floor(volume.worldToVoxel(p)));
        if (v.z < z0 || v.z >= z1 || v.x < 0 || v.y < 0 || v.x >= dims.x || v.y >= dims.y) continue;
        volume.maxMerge(v.x, v.y, v.z, density);
      }
    }
  });
  if (stats) *stats = local;
  return all;
}

}  // namespace cb
