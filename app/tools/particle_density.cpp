#include "app/tools/particle_density.h"

#include <algorithm>
#include <cmath>

#include "app/core/parallel_for.h"

namespace cb {

ParticleCounts::ParticleCounts(VoxelBox box) : box_(box) {
  size_ = box.empty() ? glm::ivec3(0) : box.hi - box.lo;
  counts_.assign(size_t(size_.x) * size_.y * size_.z, 0);
}

namespace {

// One separable tent pass along `axis` of a grid of `size`, src → dst.
void tentPass(const HugePageVector<float>& src, HugePageVector<float>* dst, glm::ivec3 size,
              int axis, int radius) {
  const size_t stride = axis == 0 ? 1 : axis == 1 ? size_t(size.x) : size_t(size.x) * size.y;
  const int len = size[axis];
  std::vector<float> weights(2 * radius + 1);
  for (int k = -radius; k <= radius; ++k) weights[k + radius] = float(radius + 1 - std::abs(k));
  float total = 0;
  for (float w : weights) total += w;
  for (float& w : weights) w /= total;
  parallelFor(size_t(size.z), 4, [&](size_t, size_t zb, size_t ze) {
    for (size_t z = zb; z < ze; ++z)
      for (int y = 0; y < size.y; ++y)
        for (int x = 0; x < size.x; ++x) {
          const int pos = axis == 0 ? x : axis == 1 ? y : int(z);
          const size_t i = (z * size.y + y) * size.x + x;
          float acc = 0;
          const int lo = std::max(-radius, -pos), hi = std::min(radius, len - 1 - pos);
          for (int k = lo; k <= hi; ++k)
            acc +=
                weights[k + radius] * src[size_t(ptrdiff_t(i) + ptrdiff_t(k) * ptrdiff_t(stride))];
          (*dst)[i] = acc;
        }
  });
}

}  // namespace

VoxelBox mergeSmoothedDensity(const ParticleCounts& counts, const DensitySmoothing& smoothing,
                              Volume* volume) {
  const glm::ivec3 size = counts.size();
  const size_t n = counts.counts().size();
  if (n == 0) return {};
  // Per-chunk maxima reduced in chunk order (a max is order-free anyway).
  constexpr size_t kGrain = size_t(1) << 16;
  const HugePageVector<uint32_t>& c = counts.counts();
  std::vector<uint32_t> chunk_count_max(chunkCount(n, kGrain), 0);
  parallelFor(n, kGrain, [&](size_t k, size_t begin, size_t end) {
    uint32_t m = 0;
    for (size_t i = begin; i < end; ++i) m = std::max(m, c[i]);
    chunk_count_max[k] = m;
  });
  uint32_t n_max = 0;
  for (uint32_t m : chunk_count_max) n_max = std::max(n_max, m);
  if (n_max == 0) return {};
  // Eq. (6): V_d = sqrt(N / N_max).
  HugePageVector<float> a(n), b(n);
  const float inv = 1.0f / float(n_max);
  parallelFor(n, kGrain, [&](size_t, size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) a[i] = std::sqrt(float(c[i]) * inv);
  });
  // Eq. (7) with a separable tent weight.
  tentPass(a, &b, size, 0, smoothing.radius_voxels);
  tentPass(b, &a, size, 1, smoothing.radius_voxels);
  tentPass(a, &b, size, 2, smoothing.radius_voxels);
  std::vector<float> chunk_peak(chunkCount(n, kGrain), 0.0f);
  parallelFor(n, kGrain, [&](size_t k, size_t begin, size_t end) {
    float m = 0;
    for (size_t i = begin; i < end; ++i) m = std::max(m, b[i]);
    chunk_peak[k] = m;
  });
  float peak = 0;
  for (float m : chunk_peak) peak = std::max(peak, m);
  if (peak <= 0) return {};
  const float scale = smoothing.peak_density / peak;
  const glm::ivec3 lo = counts.box().lo;
  // Max-merge per z slab; each slab reports the box it wrote.
  const size_t slabs = size_t(size.z);
  std::vector<VoxelBox> written(slabs);
  parallelFor(slabs, 4, [&](size_t, size_t zb, size_t ze) {
    for (size_t z = zb; z < ze; ++z) {
      VoxelBox box;
      for (int y = 0; y < size.y; ++y)
        for (int x = 0; x < size.x; ++x) {
          const float v = b[(z * size.y + y) * size.x + x] * scale;
          if (v < smoothing.cutoff) continue;
          const glm::ivec3 p = lo + glm::ivec3(x, y, int(z));
          volume->maxMerge(p.x, p.y, p.z, v);
          box = box.unite({p, p + 1});
        }
      written[z] = box;
    }
  });
  VoxelBox changed;
  for (const VoxelBox& box : written) changed = changed.unite(box);
  if (!changed.empty()) volume->markDirty(changed);
  return changed;
}

}  // namespace cb
