#include "app/mapping/edge_mapping.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "app/core/parallel_for.h"
#include "app/mapping/stroke_random.h"

namespace cb {
namespace {

struct EdgeSample {
  glm::ivec3 voxel;
  float density;
};

struct ChunkOutput {
  std::vector<EdgeSample> samples;
  VoxelBox box;
  long long mapped = 0, off_canvas = 0;
};

constexpr size_t kPixelsPerChunk = 2048;

}  // namespace

VoxelBox mapEdges(const EdgeMappingInput& in, const EdgeMappingConfig& cfg, Volume& volume,
                  EdgeMappingStats* stats) {
  EdgeMappingStats local;
  const Footprint& f = *in.footprint;
  const std::vector<Circle> no_circles;
  const std::vector<Circle>& circles = in.circles ? *in.circles : no_circles;

  // Leftover pixels in row order (the order fixes which random stream each pixel gets).
  std::vector<uint32_t> leftover;
  for (size_t i = 0; i < f.values.size(); ++i)
    if (f.values[i] > in.empty_threshold && !(in.covered && (*in.covered)[i]))
      leftover.push_back(uint32_t(i));
  local.leftover_pixels = (long long)leftover.size();

  const glm::ivec3 dims = volume.dims();
  const glm::vec3 vs = volume.voxelSize();
  const float min_depth_sigma = cfg.min_depth_sigma_voxels * std::min({vs.x, vs.y, vs.z});
  std::vector<ChunkOutput> chunks(chunkCount(leftover.size(), kPixelsPerChunk));
  parallelFor(leftover.size(), kPixelsPerChunk, [&](size_t chunk, size_t b, size_t e) {
    ChunkOutput& out = chunks[chunk];
    out.samples.reserve((e - b) * size_t(cfg.samples_per_pixel));
    int previous_nearest = -1;
    for (size_t k = b; k < e; ++k) {
      const uint32_t pixel = leftover[k];
      const int px = int(pixel % uint32_t(f.width)), py = int(pixel / uint32_t(f.width));
      glm::vec3 o, d;
      in.view->ray(float(px), float(py), &o, &d);

      glm::vec3 tangent_point;
      float depth_sigma;
      // Nearest circle by D = |p − c| − r. The previous pixel's nearest (neighbours share
      // it) seeds the search, and a circle whose |Δx| − r or |Δy| − r already reaches the best
      // D cannot win, so most circles cost no square root. The chunk's pixels always run in
      // the same order on one thread, so the answer does not depend on the thread count.
      const glm::vec2 p{float(px), float(py)};
      auto rimDistance = [&](size_t c) {
        const glm::vec2 delta = p - circles[c].centre;
        return std::sqrt(glm::dot(delta, delta)) - float(circles[c].radius);  // D_min
      };
      int nearest = previous_nearest;
      float best = nearest >= 0 ? rimDistance(size_t(nearest)) : std::numeric_limits<float>::max();
      for (size_t c = 0; c < circles.size(); ++c) {
        const float r = float(circles[c].radius);
        if (std::abs(p.x - circles[c].centre.x) - r >= best ||
            std::abs(p.y - circles[c].centre.y) - r >= best)
          continue;
        const float dist = rimDistance(c);
        if (dist < best) best = dist, nearest = int(c);
      }
      previous_nearest = nearest;
      if (nearest >= 0) {
        const MappedSphere& s = (*in.spheres)[size_t(nearest)];
        // P_t: where a sphere about P_S touches the ray, taken at P_S's view depth. Next to the
        // sphere this is the ray's closest point to P_S (§6.6.2); for a pixel far off to the
        // side the closest point slides towards the camera and the cloud would grow a tail
        // along the paint view's rays. Without edges.tangent_at_sphere_depth (journals
        // recorded before it): the closest point, as §6.6.2 writes it.
        const float along = glm::dot(d, in.view->forward());
        const float t =
            cfg.tangent_at_sphere_depth && along > 0.0f
                ? std::max(0.0f, (in.view->depthOf(s.centre) - in.view->depthOf(o)) / along)
                : std::max(0.0f, glm::dot(s.centre - o, d));
        tangent_point = o + d * t;
        depth_sigma = s.radius * cfg.depth_sigma_of_radius;
      } else {
        if (!in.view->placeOnCanvas(in.canvas, o, d, in.fallback_point, in.max_distance,
                                    &tangent_point))
          ++out.off_canvas;
        depth_sigma = in.canvas.thickness / 6.0f;
      }
      depth_sigma = std::max(depth_sigma, min_depth_sigma);
      const float lateral_sigma =
          cfg.lateral_sigma_px * in.view->pixelWorldSize(in.view->depthOf(tangent_point));
      const float density = std::min(1.0f, f.values[pixel] * cfg.density_scale);
      StrokeRandom rng(in.stroke_index, pixel);
      bool landed = false;
      for (int s = 0; s < cfg.samples_per_pixel; ++s) {
        float g_depth = rng.gaussian(), g_right = rng.gaussian(), g_up = rng.gaussian();
        glm::vec3 p = tangent_point + d * (depth_sigma * g_depth) +
                      in.view->right() * (lateral_sigma * g_right) +
                      in.view->up() * (lateral_sigma * g_up);
        glm::ivec3 v(glm::floor(volume.worldToVoxel(p)));
        if (glm::any(glm::lessThan(v, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(v, dims)))
          continue;
        out.samples.push_back({v, density});
        out.box = out.box.unite({v, v + 1});
        landed = true;
      }
      out.mapped += landed;
    }
  });

  // Max-merge in chunk order (max is order-free anyway; this keeps the box union ordered too).
  VoxelBox box;
  for (const ChunkOutput& c : chunks) {
    for (const EdgeSample& s : c.samples)
      volume.maxMerge(s.voxel.x, s.voxel.y, s.voxel.z, s.density);
    box = box.unite(c.box);
    local.mapped_pixels += c.mapped;
    local.off_canvas_pixels += c.off_canvas;
  }
  if (stats) *stats = local;
  return box;
}

}  // namespace cb
