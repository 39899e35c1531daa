#include "app/tools/model_cloud.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "app/core/parallel_for.h"
#include "app/mapping/simplex_noise.h"
#include "app/tools/distance_transform.h"
#include "app/tools/mesh_loading.h"

namespace cb {

ModelPlacement placeModel(const TriangleMesh& mesh, const ToolView& view, const Volume& volume) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::vec3& p : mesh.vertices) lo = glm::min(lo, p), hi = glm::max(hi, p);
  ModelPlacement placement;
  placement.centre = 0.5f * (lo + hi);
  placement.anchor = toolAnchor(view, volume);
  const PaintViewGeometry geometry(view.camera, view.view_width, view.view_height);
  const float world_size = geometry.pixelWorldSize(geometry.depthOf(placement.anchor)) *
                           float(view.view_height) * view.size_fraction;
  const float side = std::max(hi.x - lo.x, std::max(hi.y - lo.y, hi.z - lo.z));
  placement.scale = side > 0 ? world_size / side : 1.0f;
  return placement;
}

namespace {

// The mesh's vertices placed in continuous voxel coordinates of `volume`, and the grid around
// them: the model's voxels plus one outside layer, so the box border is outside.
VoxelBox placedVoxels(const TriangleMesh& mesh, const ModelPlacement& placement,
                      const Volume& volume, std::vector<glm::vec3>* v) {
  v->resize(mesh.vertices.size());
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (size_t i = 0; i < v->size(); ++i) {
    (*v)[i] = volume.worldToVoxel(placement.toWorld(mesh.vertices[i]));
    lo = glm::min(lo, (*v)[i]);
    hi = glm::max(hi, (*v)[i]);
  }
  return VoxelBox{glm::ivec3(glm::floor(lo)) - 1, glm::ivec3(glm::ceil(hi)) + 1};
}

}  // namespace

VoxelBox modelReach(const TriangleMesh& mesh, const ToolView& view, const Volume& volume) {
  std::vector<glm::vec3> v;
  return placedVoxels(mesh, placeModel(mesh, view, volume), volume, &v);
}

VoxelBox modelToCloud(const std::string& mesh_path, const ToolView& view,
                      const ModelCloudParams& params, Volume* volume) {
  const TriangleMesh mesh = loadClosedMesh(mesh_path);
  return meshToCloud(mesh, view, params, volume);
}

VoxelBox meshToCloud(const TriangleMesh& input, const ToolView& view,
                     const ModelCloudParams& params, Volume* volume) {
  const TriangleMesh mesh = validatedClosedMesh(input, "mesh");
  const ModelPlacement placement = placeModel(mesh, view, *volume);
  // Vertices in continuous voxel coordinates, and the grid around them.
  std::vector<glm::vec3> v;
  const VoxelBox grid = placedVoxels(mesh, placement, *volume, &v);
  const glm::ivec3 size = grid.hi - grid.lo;
  const size_t cells = size_t(size.x) * size.y * size.z;
  // Triangles per z row of the grid (by the z range of their projection).
  std::vector<std::vector<uint32_t>> by_z(size.z);
  for (uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3 tri = mesh.triangles[t];
    const float z0 = std::min({v[tri.x].z, v[tri.y].z, v[tri.z].z});
    const float z1 = std::max({v[tri.x].z, v[tri.y].z, v[tri.z].z});
    const int k0 = std::max(0, int(std::ceil(z0 - 0.5f - 1e-3f)) - grid.lo.z);
    const int k1 = std::min(size.z - 1, int(std::floor(z1 - 0.5f)) + 1 - grid.lo.z);
    for (int k = k0; k <= k1; ++k) by_z[k].push_back(t);
  }
  // Inside by parity along +x through voxel centres. The centre is nudged by an irrational
  // offset so no ray passes exactly through a vertex or along an edge of a grid-aligned mesh.
  std::vector<uint8_t> outside(cells, 1);
  constexpr float kNudgeY = 1.3e-4f, kNudgeZ = 2.9e-4f;
  parallelFor(size_t(size.z), 1, [&](size_t, size_t kb, size_t ke) {
    std::vector<std::vector<float>> hits(size.y);
    for (size_t k = kb; k < ke; ++k) {
      for (auto& h : hits) h.clear();
      const float cz = float(grid.lo.z + int(k)) + 0.5f + kNudgeZ;
      for (uint32_t t : by_z[k]) {
        const glm::uvec3 tri = mesh.triangles[t];
        const glm::vec3 a = v[tri.x], b = v[tri.y], c = v[tri.z];
        const float y0 = std::min({a.y, b.y, c.y}), y1 = std::max({a.y, b.y, c.y});
        const int j0 = std::max(0, int(std::ceil(y0 - 0.5f - kNudgeY)) - grid.lo.y);
        const int j1 = std::min(size.y - 1, int(std::floor(y1 - 0.5f - kNudgeY)) - grid.lo.y);
        for (int j = j0; j <= j1; ++j) {
          const float cy = float(grid.lo.y + j) + 0.5f + kNudgeY;
          // Barycentric coordinates of (cy, cz) in the triangle's yz projection.
          const float d = (b.y - a.y) * (c.z - a.z) - (c.y - a.y) * (b.z - a.z);
          if (d == 0.0f) continue;
          const float w1 = ((cy - a.y) * (c.z - a.z) - (c.y - a.y) * (cz - a.z)) / d;
          const float w2 = ((b.y - a.y) * (cz - a.z) - (cy - a.y) * (b.z - a.z)) / d;
          if (w1 < 0 || w2 < 0 || w1 + w2 > 1) continue;
          hits[j].push_back(a.x + w1 * (b.x - a.x) + w2 * (c.x - a.x));
        }
      }
      for (int j = 0; j < size.y; ++j) {
        std::vector<float>& h = hits[j];
        std::sort(h.begin(), h.end());
        for (size_t p = 0; p + 1 < h.size(); p += 2) {
          const int i0 = std::max(0, int(std::ceil(h[p] - 0.5f)) - grid.lo.x);
          const int i1 = std::min(size.x - 1, int(std::ceil(h[p + 1] - 0.5f)) - 1 - grid.lo.x);
          for (int i = i0; i <= i1; ++i) outside[(k * size.y + j) * size.x + i] = 0;
        }
      }
    }
  });
  // Depth below the surface, in voxels.
  std::vector<float> d2;
  squaredDistance3d(size.x, size.y, size.z, outside, &d2);
  const SimplexNoise3 noise(params.seed);
  const VoxelBox target = grid.intersect(volume->bounds());
  if (target.empty()) return {};
  std::vector<VoxelBox> written(size.z);
  parallelFor(size_t(size.z), 2, [&](size_t, size_t kb, size_t ke) {
    for (size_t k = kb; k < ke; ++k) {
      VoxelBox box;
      const int z = grid.lo.z + int(k);
      if (z < target.lo.z || z >= target.hi.z) continue;
      for (int y = std::max(grid.lo.y, target.lo.y); y < std::min(grid.hi.y, target.hi.y); ++y)
        for (int x = std::max(grid.lo.x, target.lo.x); x < std::min(grid.hi.x, target.hi.x); ++x) {
          const size_t c = (k * size.y + (y - grid.lo.y)) * size.x + (x - grid.lo.x);
          if (outside[c]) continue;
          // Distance from the voxel centre to the surface ≈ distance to the nearest outside
          // centre minus half a voxel.
          const float depth = std::sqrt(d2[c]) - 0.5f;
          float density = params.peak_density;
          const float band = params.falloff_voxels + params.noise_erosion_voxels;
          if (depth < band) {
            const glm::vec3 world = volume->voxelToWorld(glm::vec3(x, y, z) + 0.5f);
            const float n = 0.5f + 0.5f * noise(world * params.noise_frequency);
            const float eroded = depth - params.noise_erosion_voxels * n;
            density *= std::clamp(eroded / params.falloff_voxels, 0.0f, 1.0f);
          }
          if (density <= 0) continue;
          volume->maxMerge(x, y, z, density);
          box = box.unite({{x, y, z}, {x + 1, y + 1, z + 1}});
        }
      written[k] = box;
    }
  });
  VoxelBox changed;
  for (const VoxelBox& b : written) changed = changed.unite(b);
  if (!changed.empty()) volume->markDirty(changed);
  return changed;
}

}  // namespace cb
