#include "app/mapping/sphere_mapping.h"

#include <algorithm>
#include <cmath>

#include "app/core/parallel_for.h"

namespace cb {

std::vector<MappedSphere> mapCirclesToSpheres(const std::vector<Circle>& circles,
                                              const PaintViewGeometry& view, const Canvas& canvas,
                                              glm::vec3 fallback_point, float max_distance) {
  std::vector<MappedSphere> spheres;
  spheres.reserve(circles.size());
  for (const Circle& c : circles) {
    glm::vec3 o, d, p;
    view.ray(c.centre.x, c.centre.y, &o, &d);
    MappedSphere s;
    s.on_canvas = view.placeOnCanvas(canvas, o, d, fallback_point, max_distance, &p);
    s.centre = p;
    s.radius = float(c.radius) * view.pixelWorldSize(view.depthOf(p));
    spheres.push_back(s);
  }
  return spheres;
}

VoxelBox sphereVoxelBox(const MappedSphere& s, const Volume& volume) {
  glm::vec3 lo = volume.worldToVoxel(s.centre - glm::vec3(s.radius));
  glm::vec3 hi = volume.worldToVoxel(s.centre + glm::vec3(s.radius));
  VoxelBox box{glm::ivec3(glm::floor(lo)), glm::ivec3(glm::floor(hi)) + 1};
  return box.intersect(volume.bounds());
}

VoxelBox fillSpheres(const std::vector<MappedSphere>& spheres, const NoiseTexture& noise,
                     const SphereMappingConfig& config, Volume& volume) {
  // The filled spheres: the circle's sphere widened so its noise-eroded surface straddles the
  // circle's outline in the paint view instead of lying inside it (see sphereFillRadius).
  std::vector<MappedSphere> filled = spheres;
  const glm::vec3 voxel = volume.voxelSize();
  const float voxel_size = std::min({voxel.x, voxel.y, voxel.z});
  for (MappedSphere& s : filled)
    if (s.radius > 0.0f) s.radius = sphereFillRadius(s.radius, voxel_size, config);
  std::vector<VoxelBox> boxes(filled.size());
  VoxelBox all;
  for (size_t i = 0; i < filled.size(); ++i) {
    boxes[i] = filled[i].radius > 0.0f ? sphereVoxelBox(filled[i], volume) : VoxelBox{};
    all = all.unite(boxes[i]);
  }
  if (all.empty()) return {};
  const glm::vec3 vs = volume.voxelSize(), wmin = volume.worldMin();
  const size_t depth = size_t(all.hi.z - all.lo.z);
  parallelFor(depth, 2, [&](size_t, size_t k0, size_t k1) {
    for (size_t k = k0; k < k1; ++k) {
      const int z = all.lo.z + int(k);
      const float wz = wmin.z + (float(z) + 0.5f) * vs.z;
      for (size_t i = 0; i < filled.size(); ++i) {
        const VoxelBox& b = boxes[i];
        if (b.empty() || z < b.lo.z || z >= b.hi.z) continue;
        const MappedSphere& s = filled[i];
        const float inv_r = 1.0f / s.radius;
        const float dz = wz - s.centre.z;
        for (int y = b.lo.y; y < b.hi.y; ++y) {
          const float dy = wmin.y + (float(y) + 0.5f) * vs.y - s.centre.y;
          const float dyz2 = dy * dy + dz * dz;
          if (dyz2 >= s.radius * s.radius) continue;
          for (int x = b.lo.x; x < b.hi.x; ++x) {
            const float dx = wmin.x + (float(x) + 0.5f) * vs.x - s.centre.x;
            const float q = std::sqrt(dx * dx + dyz2) * inv_r;
            if (q >= 1.0f) continue;
            const float v = sphereDensity(q, noise.at(x, y, z), config);
            volume.maxMerge(x, y, z, v);
          }
        }
      }
    }
  });
  return all;
}

}  // namespace cb
