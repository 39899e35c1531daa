#include "app/mapping/sheet_mapping.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

#include "app/core/parallel_for.h"

namespace cb {
namespace {

// Footprint value at continuous pixel coordinates (pixel centres at +0.5), 0 outside.
float bilinear(const Footprint& f, float u, float v) {
  const float x = u - 0.5f, y = v - 0.5f;
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const float fx = x - float(x0), fy = y - float(y0);
  const auto at = [&](int px, int py) { return f.inside(px, py) ? f.at(px, py) : 0.0f; };
  return (at(x0, y0) * (1 - fx) + at(x0 + 1, y0) * fx) * (1 - fy) +
         (at(x0, y0 + 1) * (1 - fx) + at(x0 + 1, y0 + 1) * fx) * fy;
}

}  // namespace

VoxelBox mapSheet(const Footprint& f, const Camera& camera, const Canvas& canvas,
                  const SheetConfig& config, const NoiseTexture& noise, float empty_threshold,
                  Volume& volume, SheetStats* stats) {
  // The footprint's inked pixels bound the layer: their rays on the mid-plane give its x/z box.
  int x_lo = f.width, x_hi = -1, y_lo = f.height, y_hi = -1;
  float peak = 0.0f;
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) {
      const float v = f.at(x, y);
      if (!(v > empty_threshold)) continue;
      x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x);
      y_lo = std::min(y_lo, y), y_hi = std::max(y_hi, y);
      peak = std::max(peak, v);
    }
  if (x_hi < 0) return {};
  glm::vec2 lo(1e30f), hi(-1e30f);
  for (glm::vec2 corner : {glm::vec2(x_lo, y_lo), glm::vec2(x_hi + 1, y_lo),
                           glm::vec2(x_lo, y_hi + 1), glm::vec2(x_hi + 1, y_hi + 1)}) {
    glm::vec3 origin, dir;
    camera.pixelRay(corner.x - 0.5f, corner.y - 0.5f, f.width, f.height, &origin, &dir);
    float t = 0.0f;
    // A corner whose ray misses the plane (above the horizon) leaves the box to the volume.
    if (!canvas.intersectMidPlane(origin, dir, &t)) {
      lo = glm::vec2(volume.worldMin().x, volume.worldMin().z);
      hi = glm::vec2(volume.worldMax().x, volume.worldMax().z);
      break;
    }
    const glm::vec3 p = origin + t * dir;
    lo = glm::min(lo, glm::vec2(p.x, p.z));
    hi = glm::max(hi, glm::vec2(p.x, p.z));
  }
  const glm::vec3 voxel = volume.voxelSize();
  const float sigma = config.sigma_voxels * voxel.y;
  const glm::vec3 wlo(lo.x, canvas.altitude - 3.0f * sigma, lo.y);
  const glm::vec3 whi(hi.x, canvas.altitude + 3.0f * sigma, hi.y);
  const VoxelBox box = VoxelBox{glm::ivec3(glm::floor(volume.worldToVoxel(wlo))) - 1,
                                glm::ivec3(glm::ceil(volume.worldToVoxel(whi))) + 1}
                           .intersect(volume.bounds());
  if (box.empty()) return {};
  const glm::mat4 view_projection =
      camera.projection(float(f.width) / float(f.height)) * camera.view();
  const float inv_peak = 1.0f / peak;
  const int slabs = box.hi.z - box.lo.z;
  std::vector<long long> counts(size_t(slabs), 0);
  std::vector<VoxelBox> touched(static_cast<size_t>(slabs));
  parallelFor(size_t(slabs), 1, [&](size_t, size_t begin, size_t end) {
    for (size_t s = begin; s < end; ++s) {
      const int z = box.lo.z + int(s);
      for (int x = box.lo.x; x < box.hi.x; ++x) {
        // The column's point on the mid-plane, seen in the paint view.
        const glm::vec3 w = volume.voxelToWorld(glm::vec3(x + 0.5f, 0.0f, z + 0.5f));
        const glm::vec4 clip = view_projection * glm::vec4(w.x, canvas.altitude, w.z, 1.0f);
        if (clip.w <= 1e-6f) continue;
        const float u = (clip.x / clip.w * 0.5f + 0.5f) * float(f.width);
        const float v = (0.5f - clip.y / clip.w * 0.5f) * float(f.height);
        const float ink = bilinear(f, u, v) * inv_peak;
        if (!(ink > empty_threshold)) continue;
        for (int y = box.lo.y; y < box.hi.y; ++y) {
          const float wy = volume.voxelToWorld(glm::vec3(0.0f, y + 0.5f, 0.0f)).y;
          const float d = (wy - canvas.altitude) / sigma;
          const float erosion = 1.0f - config.erosion * (0.5f + 0.5f * noise.at(x, y, z));
          const float density = std::min(1.0f, ink * std::exp(-0.5f * d * d) * erosion);
          if (density < 1.0f / 255.0f) continue;
          if (volume.maxMerge(x, y, z, density)) {
            ++counts[s];
            touched[s] = touched[s].unite({{x, y, z}, {x + 1, y + 1, z + 1}});
          }
        }
      }
    }
  });
  VoxelBox dirty;
  long long voxels = 0;
  for (size_t s = 0; s < touched.size(); ++s) {
    dirty = dirty.unite(touched[s]);
    voxels += counts[s];
  }
  if (stats) stats->voxels = voxels;
  return dirty;
}

}  // namespace cb
