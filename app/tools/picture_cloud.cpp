#include "app/tools/picture_cloud.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "app/core/parallel_for.h"
#include "app/mapping/stroke_random.h"
#include "app/tools/distance_transform.h"
#include "app/tools/tool_error.h"

namespace cb {
namespace {

constexpr int kAngleBins = 720;

// Medial axis pixels (§3.1.1.1): ridges of the interior distance to the background — pixels
// whose distance is not smaller than both neighbours' along x or along y.
std::vector<uint8_t> medialAxis(const ShapeMask& mask) {
  std::vector<uint8_t> outside(mask.inside.size());
  for (size_t i = 0; i < outside.size(); ++i) outside[i] = !mask.inside[i];
  std::vector<float> d2;
  squaredDistance2d(mask.width, mask.height, outside, &d2, nullptr);
  const int w = mask.width, h = mask.height;
  auto at = [&](int x, int y) {
    if (x < 0 || y < 0 || x >= w || y >= h) return 0.0f;
    const float v = d2[size_t(y) * w + x];
    return std::isinf(v) ? 1e30f : v;  // an image with no background: all interior
  };
  std::vector<uint8_t> axis(mask.inside.size(), 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!mask.at(x, y)) continue;
      const float c = at(x, y);
      const bool ridge_x = c >= at(x - 1, y) && c >= at(x + 1, y);
      const bool ridge_y = c >= at(x, y - 1) && c >= at(x, y + 1);
      axis[size_t(y) * w + x] = ridge_x || ridge_y;
    }
  return axis;
}

// §3.1.1.2: centre (x_e, y_e) and D_max per direction from it (the shape's outermost extent
// along each of kAngleBins directions); Eq. (2.1) R = D_max − D. `mask` has a shape pixel.
struct ShapeSpread {
  explicit ShapeSpread(const ShapeMask& mask) : extent(kAngleBins, 0.0f) {
    const int w = mask.width, h = mask.height;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        if (mask.at(x, y)) cx += x + 0.5, cy += y + 0.5;
    const double count = double(mask.count());
    cx /= count;
    cy /= count;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        if (!mask.at(x, y)) continue;
        // The pixel's far corner distance, so R stays > 0 inside the outermost pixel.
        const float dx = float(x + 0.5 - cx), dy = float(y + 0.5 - cy);
        const int b = binOf(dx, dy);
        extent[b] = std::max(extent[b], std::sqrt(dx * dx + dy * dy) + 0.7072f);
      }
    // Bins no pixel fell into (thin shapes far from the centre) take the larger neighbour.
    for (int pass = 0; pass < 2; ++pass)
      for (int b = 0; b < kAngleBins; ++b)
        if (extent[b] == 0.0f)
          extent[b] =
              std::max(extent[(b + kAngleBins - 1) % kAngleBins], extent[(b + 1) % kAngleBins]);
    for (float e : extent) r_max = std::max(r_max, e);
  }
  static int binOf(float dx, float dy) {
    const float a = std::atan2(dy, dx);  // [-pi, pi]
    int b = int((a + float(M_PI)) * (kAngleBins / (2.0f * float(M_PI))));
    return std::clamp(b, 0, kAngleBins - 1);
  }
  double cx = 0, cy = 0;
  std::vector<float> extent;
  float r_max = 0;  // the largest D_max: the deepest any particle is stretched (Eq. 2.4)
};

// The box the particles can reach: the picture's corners at the nearest and farthest depth
// (±r_max·texel·depth_scale about the anchor plane), grown by the smoothing's radius + 1; in
// `volume`'s voxel grid, not clipped to it.
VoxelBox reachBox(const PicturePlacement& placement, int w, int h, float r_max,
                  const PictureCloudParams& params, const Volume& volume) {
  const float z_extent = r_max * placement.pictureTexelWorldSize() * params.depth_scale;
  VoxelBox reach;
  for (int c = 0; c < 8; ++c) {
    const glm::vec2 corner((c & 1) ? float(w) : 0.0f, (c & 2) ? float(h) : 0.0f);
    const glm::vec3 p = placement.worldPoint(corner, (c & 4) ? z_extent : -z_extent);
    const glm::ivec3 v = glm::ivec3(glm::floor(volume.worldToVoxel(p)));
    reach = reach.unite({v, v + 1});
  }
  return reach.grow(params.smoothing.radius_voxels + 1);
}

void requireShape(const ShapeMask& mask) {
  if (mask.width <= 0 || mask.height <= 0 || mask.count() == 0)
    throw ToolError(ToolErrorKind::kEmptyImage, "the picture has no shape pixel");
}

// §3.1.1.1: the nearest medial-axis pixel q of every pixel (-1: none) and d_max, the largest
// distance d_pq of a shape pixel to its q.
struct MedialAxisPull {
  std::vector<int> nearest;
  float d_max = 0;
};

MedialAxisPull medialAxisPull(const ShapeMask& mask) {
  MedialAxisPull pull;
  const std::vector<uint8_t> axis = medialAxis(mask);
  std::vector<float> axis_d2;
  squaredDistance2d(mask.width, mask.height, axis, &axis_d2, &pull.nearest);
  for (size_t i = 0; i < axis_d2.size(); ++i)
    if (mask.inside[i]) pull.d_max = std::max(pull.d_max, std::sqrt(axis_d2[i]));
  return pull;
}

}  // namespace

VoxelBox pictureReach(const ShapeMask& mask, const ToolView& view, const PictureCloudParams& params,
                      const Volume& volume) {
  requireShape(mask);
  const PicturePlacement placement(view, volume, mask.width, mask.height);
  return reachBox(placement, mask.width, mask.height, ShapeSpread(mask).r_max, params, volume);
}

VoxelBox pictureToCloud(const std::string& png_path, const ToolView& view,
                        const PictureCloudParams& params, Volume* volume) {
  const ShapeMask mask = loadShapeMask(png_path);
  return maskToCloud(mask, view, params, volume);
}

namespace {

// Picture rows per parallelFor chunk in the particle walks.
constexpr size_t kPictureRowsPerChunk = 8;

// The particles wanted over the shape by Eq. (5) (D × column volume / voxel volume, a column of
// range R holding an effective depth of about R), and the factor that scales them down to at
// most params.max_particles (1 when they fit).
template <class RangeOf>
double particleBudgetFactor(const ShapeMask& mask, const RangeOf& rangeOf, float texel,
                            float voxel_volume, const PictureCloudParams& params) {
  double wanted = 0;
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x)
      if (mask.at(x, y))
        wanted += double(texel) * texel * (rangeOf(x, y) * texel * params.depth_scale) /
                  voxel_volume * params.particles_per_voxel;
  return wanted > double(params.max_particles) ? double(params.max_particles) / wanted : 1.0;
}

// The voxel box the particles of rows 0..h-1 occupy (forEachParticleOfRow(y, sink) calls sink
// with each particle's world position), walked in row chunks in parallel and united in chunk
// order.
template <class ForEachParticleOfRow>
VoxelBox occupiedBox(int h, const Volume& volume,
                     const ForEachParticleOfRow& forEachParticleOfRow) {
  std::vector<VoxelBox> chunk_box(chunkCount(size_t(h), kPictureRowsPerChunk));
  parallelFor(size_t(h), kPictureRowsPerChunk, [&](size_t k, size_t y_begin, size_t y_end) {
    glm::ivec3 lo(std::numeric_limits<int>::max()), hi(std::numeric_limits<int>::min());
    for (size_t y = y_begin; y < y_end; ++y)
      forEachParticleOfRow(int(y), [&](glm::vec3 world) {
        const glm::ivec3 v = glm::ivec3(glm::floor(volume.worldToVoxel(world)));
        lo = glm::min(lo, v);
        hi = glm::max(hi, v + 1);
      });
    if (lo.x <= hi.x) chunk_box[k] = VoxelBox{lo, hi};
  });
  VoxelBox occupied;
  for (const VoxelBox& box : chunk_box) occupied = occupied.unite(box);
  return occupied;
}

}  // namespace

VoxelBox maskToCloud(const ShapeMask& mask, const ToolView& view, const PictureCloudParams& params,
                     Volume* volume) {
  requireShape(mask);
  const int w = mask.width, h = mask.height;
  const PicturePlacement placement(view, *volume, w, h);
  const float texel = placement.pictureTexelWorldSize();

  const MedialAxisPull pull = params.naive_uniform_depth ? MedialAxisPull{} : medialAxisPull(mask);
  const std::vector<int>& axis_nearest = pull.nearest;
  const float d_max = pull.d_max;

  const ShapeSpread spread(mask);
  const double cx = spread.cx, cy = spread.cy;
  const std::vector<float>& extent = spread.extent;
  const float r_max = spread.r_max;
  auto binOf = [](float dx, float dy) { return ShapeSpread::binOf(dx, dy); };

  // Particles per pixel from Eq. (5): D × (column volume / voxel volume); the column of a pixel
  // with range R holds, for the pdf of Eq. (2.2), an effective depth of about R.
  const glm::vec3 vs = volume->voxelSize();
  const float voxel_volume = vs.x * vs.y * vs.z;
  auto rangeOf = [&](int x, int y) {
    const float dx = float(x + 0.5 - cx), dy = float(y + 0.5 - cy);
    const float d = std::sqrt(dx * dx + dy * dy);
    return std::max(0.5f, extent[binOf(dx, dy)] - d);  // Eq. (2.1), in picture pixels
  };
  const double density_factor = particleBudgetFactor(mask, rangeOf, texel, voxel_volume, params);

  const VoxelBox reach =
      reachBox(placement, w, h, r_max, params, *volume).intersect(volume->bounds());
  if (reach.empty()) return {};

  // The anchor plane is affine in picture coordinates; a depth offset scales along the eye ray.
  const glm::vec3 p00 = placement.worldPoint({0, 0}, 0);
  const glm::vec3 du = placement.worldPoint({1, 0}, 0) - p00;
  const glm::vec3 dv = placement.worldPoint({0, 1}, 0) - p00;
  const glm::vec3 eye = view.camera.eye;
  const float anchor_depth = glm::dot(placement.anchor() - eye, placement.forward());

  // Calls sink(world) for every particle of picture row y, in a fixed order: the particles of a
  // pixel depend only on (seed, pixel), so two walks over a row draw the same particles.
  auto forEachParticleOfRow = [&](int y, auto&& sink) {
    for (int x = 0; x < w; ++x) {
      if (!mask.at(x, y)) continue;
      const size_t pixel = size_t(y) * w + x;
      StrokeRandom rng(params.seed, pixel);
      const float range = rangeOf(x, y);
      const double expected = double(texel) * texel * (range * texel * params.depth_scale) /
                              voxel_volume * params.particles_per_voxel * density_factor;
      // Stochastic rounding, at least one particle per shape pixel.
      int n = int(expected);
      if (rng.uniform() < expected - n) ++n;
      n = std::max(n, 1);
      glm::vec2 to_axis(0);
      float d_pq = 0;
      if (!params.naive_uniform_depth && axis_nearest[pixel] >= 0) {
        const int q = axis_nearest[pixel];
        to_axis = glm::vec2(float(q % w - x), float(q / w - y));
        d_pq = glm::length(to_axis);
      }
      for (int i = 0; i < n; ++i) {
        // Stratified: uniform within the pixel.
        glm::vec2 p(x + float(rng.uniform()), y + float(rng.uniform()));
        float z;
        if (params.naive_uniform_depth) {
          z = float(2.0 * rng.uniform() - 1.0) * r_max;
        } else {
          // Eq. (1): p' = p + (d_pq / d_max) · ε · N_pq, N_pq = q − p (length d_pq).
          if (d_max > 0) {
            const float eps = float(rng.uniform()) * params.medial_pull;
            p += (d_pq / d_max) * eps * to_axis;
          }
          // Eq. (2.4): z' = R − R·sqrt(1 − ε), on either side of the anchor plane.
          const float e = float(rng.uniform());
          z = range - range * std::sqrt(1.0f - e);
          if (rng.next() & 1) z = -z;
        }
        const float offset = z * texel * params.depth_scale;
        const glm::vec3 on_plane = p00 + p.x * du + p.y * dv;
        sink(eye + (on_plane - eye) * ((anchor_depth + offset) / anchor_depth));
      }
    }
  };

  // First walk: the voxel box the particles occupy. The counts and smoothing grids then cover
  // that box grown by the smoothing radius (+1) rather than the whole reachable box — less
  // memory to fault in and to smooth, and the same bytes: the tent pass only ever adds zeros
  // from the cells this drops.
  const VoxelBox occupied = occupiedBox(h, *volume, forEachParticleOfRow);
  const VoxelBox grid = occupied.grow(params.smoothing.radius_voxels + 1).intersect(reach);
  if (grid.empty()) return {};

  // Second walk: count.
  ParticleCounts counts(grid);
  parallelFor(size_t(h), kPictureRowsPerChunk, [&](size_t, size_t y_begin, size_t y_end) {
    for (size_t y = y_begin; y < y_end; ++y)
      forEachParticleOfRow(int(y), [&](glm::vec3 world) { counts.add(*volume, world); });
  });
  return mergeSmoothedDensity(counts, params.smoothing, volume);
}

}  // namespace cb
