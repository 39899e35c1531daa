#include "app/tools/cloud_morph_cells.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace cb {
namespace {

struct PlacedSplat {
  glm::vec3 p;  // continuous index, clamped to the grid (voxel centres at integers)
  float mass;
};

// Every non-empty voxel of one side, z, y, x order, once per path of its cell.
void placeSide(const MorphPlan& plan, const Volume& cloud, bool from_source, float t,
               std::vector<PlacedSplat>* placed) {
  const MorphParams& params = plan.params();
  const MorphPlan::Side& side = plan.side(from_source);
  const glm::ivec3 d = cloud.dims(), cells = plan.cells();
  const glm::vec3 top(d - 1);
  const float weight = from_source ? 1.0f - t : t;
  const float s = 1.0f - t;
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        const float m = cloud.at(x, y, z);
        if (m <= params.density_threshold) continue;
        const glm::ivec3 c = glm::ivec3(x, y, z) / params.cell_voxels;
        const int particle = side.cell_particle[(size_t(c.z) * cells.y + c.y) * cells.x + c.x];
        const std::vector<uint32_t>& paths = side.particle_paths[size_t(particle)];
        const float mass = m / float(paths.size());
        for (uint32_t k : paths) {
          const MorphPlan::Path& path = plan.paths()[k];
          const glm::vec3 anchor = from_source ? path.source : path.target;
          const glm::vec3 offset = glm::vec3(x, y, z) + 0.5f - anchor;
          const glm::vec3 at =
              s * s * path.source + 2.0f * s * t * path.refine + t * t * path.target;
          placed->push_back({glm::clamp(offset + at - 0.5f, glm::vec3(0.0f), top), weight * mass});
        }
      }
}

}  // namespace

Volume morphCellBlocks(const Volume& source, const Volume& target, float t,
                       const MorphParams& params) {
  const MorphPlan plan(source, target, params);
  t = std::clamp(t, 0.0f, 1.0f);
  const glm::ivec3 dims = source.dims();
  // t = 0 carries only the source, t = 1 only the target (exact ends).
  std::vector<PlacedSplat> placed;
  if (t < 1.0f) placeSide(plan, source, true, t, &placed);
  if (t > 0.0f) placeSide(plan, target, false, t, &placed);
  auto baseOf = [&](glm::vec3 p) { return glm::min(glm::ivec3(glm::floor(p)), dims - 1); };
  // Stable counting sort by the z plane of the base corner.
  std::vector<size_t> plane_start(size_t(dims.z) + 1, 0);
  for (const PlacedSplat& p : placed) ++plane_start[size_t(baseOf(p.p).z) + 1];
  for (int z = 0; z < dims.z; ++z) plane_start[size_t(z) + 1] += plane_start[size_t(z)];
  std::vector<PlacedSplat> sorted(placed.size());
  std::vector<size_t> next(plane_start.begin(), plane_start.end() - 1);
  for (const PlacedSplat& p : placed) sorted[next[size_t(baseOf(p.p).z)]++] = p;
  // Each plane adds the splats based one plane below (their upper corners), then its own.
  Volume out(dims, source.worldMin(), source.worldMax());
  for (size_t z = 0; z < size_t(dims.z); ++z) {
    for (int upper = 1; upper >= 0; --upper) {
      if (upper && z == 0) continue;
      for (size_t i = plane_start[z - size_t(upper)]; i < plane_start[z - upper + 1]; ++i) {
        const PlacedSplat& s = sorted[i];
        const glm::ivec3 base = baseOf(s.p);
        const glm::vec3 f = s.p - glm::vec3(base);
        const float wz = upper ? f.z : 1.0f - f.z;
        if (wz == 0.0f) continue;
        for (int c = 0; c < 4; ++c) {
          const int ox = c & 1, oy = c >> 1;
          const float w = (ox ? f.x : 1 - f.x) * (oy ? f.y : 1 - f.y) * wz;
          if (w == 0.0f) continue;
          const int qx = std::min(base.x + ox, dims.x - 1), qy = std::min(base.y + oy, dims.y - 1);
          out.voxelForWrite(qx, qy, int(z)) += w * s.mass;
        }
      }
    }
  }
  out.markDirty(out.bounds());
  return out;
}

}  // namespace cb
