// Particles → smooth voxel densities (seed 002 §3.1.3) and the max-merge into the volume.
// Particles are counted per voxel of a box (atomic integer counts: the same total on any thread
// count), Eq. (6) turns counts into V_d = sqrt(N / N_max), and Eq. (7)'s weighted neighbourhood
// sum is taken at every voxel with a separable tent kernel of radius R (the seed names the
// inverse-distance weight only as "a simple case"; a tent is separable, so the smoothing costs
// O(R) per voxel instead of O(R³)).
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "app/tools/huge_page_allocator.h"
#include "app/volume/box.h"
#include "app/volume/volume.h"

namespace cb {

class ParticleCounts {
 public:
  explicit ParticleCounts(VoxelBox box);
  const VoxelBox& box() const { return box_; }
  // Counts a particle at a world point (ignored outside the box). Thread-safe.
  void add(const Volume& volume, glm::vec3 world) {
    const glm::ivec3 v = glm::ivec3(glm::floor(volume.worldToVoxel(world)));
    if (!box_.contains(v)) return;
    const glm::ivec3 l = v - box_.lo;
    std::atomic_ref<uint32_t>(counts_[(size_t(l.z) * size_.y + l.y) * size_.x + l.x])
        .fetch_add(1, std::memory_order_relaxed);
  }
  const HugePageVector<uint32_t>& counts() const { return counts_; }
  glm::ivec3 size() const { return size_; }

 private:
  VoxelBox box_;
  glm::ivec3 size_;
  HugePageVector<uint32_t> counts_;
};

struct DensitySmoothing {
  int radius_voxels = 2;      // R of Eq. (7)
  float peak_density = 1.0f;  // the smoothed field's maximum maps to this
  float cutoff = 0.02f;       // densities below this (after scaling) stay 0
};

// Eq. (6) and (7) on the counts, scaled so the maximum is peak_density, max-merged into the
// volume. Returns the box of voxels that received density (empty if none) and marks it dirty.
VoxelBox mergeSmoothedDensity(const ParticleCounts& counts, const DensitySmoothing& smoothing,
                              Volume* volume);

}  // namespace cb
