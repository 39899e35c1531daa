// The volume is the hub of the system (thesis §3.3): a dense float density grid placed as a sky
// box in world space. Every change records a dirty box; each consumer (renderer upload,
// occupancy, light volume, history) remembers the generation it last saw and asks for the union
// of what changed since.
#pragma once

#include <cstdint>
#include <deque>
#include <vector>

#include <glm/glm.hpp>

#include "app/volume/box.h"

namespace cb {

// The largest grid along any axis.
constexpr int kMaxVolumeDim = 2048;

class Volume {
 public:
  // dims voxels, occupying the world-space box [world_min, world_max] (y is up). Each dim must be
  // in 1..kMaxVolumeDim (else std::invalid_argument).
  explicit Volume(glm::ivec3 dims = glm::ivec3(256), glm::vec3 world_min = glm::vec3(-1.0f),
                  glm::vec3 world_max = glm::vec3(1.0f));

  // Every construction or assignment gets a new process-unique id, so a consumer that tracks
  // (id, generation) never mistakes a different volume at the same address for the one it saw.
  Volume(const Volume& o);
  Volume(Volume&& o) noexcept;
  Volume& operator=(const Volume& o);
  Volume& operator=(Volume&& o) noexcept;
  uint64_t instanceId() const { return instance_id_; }

  glm::ivec3 dims() const { return dims_; }
  glm::vec3 worldMin() const { return world_min_; }
  glm::vec3 worldMax() const { return world_max_; }
  VoxelBox bounds() const { return {glm::ivec3(0), dims_}; }
  size_t voxelCount() const { return data_.size(); }

  size_t index(int x, int y, int z) const {
    return (size_t(z) * dims_.y + size_t(y)) * dims_.x + size_t(x);
  }
  float at(int x, int y, int z) const { return data_[index(x, y, z)]; }
  // Raw access (x fastest, then y, then z). Writers must call markDirty() for what they touched.
  float* data() { return data_.data(); }
  const float* data() const { return data_.data(); }

  void set(int x, int y, int z, float v) {
    data_[index(x, y, z)] = v;
    markDirty({{x, y, z}, {x + 1, y + 1, z + 1}});
  }
  void fill(float v);

  // Records a change (clipped to bounds) and returns the new generation.
  uint64_t markDirty(const VoxelBox& box);
  uint64_t generation() const { return generation_; }
  // Union of every box marked after generation `since` (the whole volume if that is older
  // than the kept history).
  VoxelBox dirtySince(uint64_t since) const;

  // World <-> voxel coordinates. Voxel (i,j,k) covers [i,i+1) in continuous voxel space; its
  // centre is at i+0.5.
  glm::vec3 voxelSize() const { return (world_max_ - world_min_) / glm::vec3(dims_); }
  glm::vec3 worldToVoxel(glm::vec3 w) const { return (w - world_min_) / voxelSize(); }
  glm::vec3 voxelToWorld(glm::vec3 v) const { return world_min_ + v * voxelSize(); }

 private:
  glm::ivec3 dims_;
  glm::vec3 world_min_, world_max_;
  std::vector<float> data_;
  uint64_t generation_ = 0;
  uint64_t instance_id_;
  struct Change {
    uint64_t generation;
    VoxelBox box;
  };
  std::deque<Change> changes_;  // most recent last, bounded
};

}  // namespace cb
