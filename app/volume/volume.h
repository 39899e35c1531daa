// The volume is the hub of the system (thesis §3.3): a density grid placed as a sky box in world
// space. It is sparse: the grid is cut into 16³ bricks (the bricks of the undo history and the
// renderer's occupancy), and a brick's memory exists only once something non-zero was written
// into it; an unallocated brick reads as zero. So an empty sky costs the brick table alone
// (8 bytes and one generation per brick), whatever its extent.
//
// Every change records a dirty box; each consumer (renderer upload, occupancy, light volume,
// history) remembers the generation it last saw and asks for the union of what changed since
// (`dirtySince`) or for the bricks that changed (`changedBricksSince`, exact at any age).
//
// Writers go through the brick-aware accessors (`set`, `maxMerge`, `voxelForWrite`,
// `writeLine`) and then call markDirty() for what they touched. The allocating accessors may be
// called from several threads at once (mapping fills z slabs in parallel); markDirty, fill,
// clear and releaseEmptyBrick belong to one thread.
#pragma once

#include <atomic>
#include <bit>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <vector>

#include <glm/glm.hpp>

#include "app/volume/box.h"

namespace cb {

// The largest grid along any axis.
constexpr int kMaxVolumeDim = 2048;

class Volume {
 public:
  // Bricks are 16³ voxels (x fastest inside a brick), the size of the history's XOR deltas and
  // of the renderer's occupancy cells: one brick is one 16 KiB allocation, small enough that a
  // stroke allocates little beyond its own voxels, large enough that the brick table stays
  // small (64·16·64 entries for a 1024×256×1024 sky).
  static constexpr int kBrickShift = 4;
  static constexpr int kBrickSize = 1 << kBrickShift;
  static constexpr int kBrickVoxels = kBrickSize * kBrickSize * kBrickSize;
  static constexpr size_t kBrickBytes = size_t(kBrickVoxels) * sizeof(float);

  // dims voxels, occupying the world-space box [world_min, world_max] (y is up). Each dim must be
  // in 1..kMaxVolumeDim (else std::invalid_argument). No brick is allocated: the volume is zero.
  explicit Volume(glm::ivec3 dims = glm::ivec3(256), glm::vec3 world_min = glm::vec3(-1.0f),
                  glm::vec3 world_max = glm::vec3(1.0f));

  // Every construction or assignment gets a new process-unique id, so a consumer that tracks
  // (id, generation) never mistakes a different volume at the same address for the one it saw.
  Volume(const Volume& o);
  Volume(Volume&& o) noexcept;
  Volume& operator=(const Volume& o);
  Volume& operator=(Volume&& o) noexcept;
  ~Volume();
  uint64_t instanceId() const { return instance_id_; }

  glm::ivec3 dims() const { return dims_; }
  glm::vec3 worldMin() const { return world_min_; }
  glm::vec3 worldMax() const { return world_max_; }
  VoxelBox bounds() const { return {glm::ivec3(0), dims_}; }
  // Voxels of the whole extent (allocated or not).
  size_t voxelCount() const { return size_t(dims_.x) * size_t(dims_.y) * size_t(dims_.z); }
  // The position of voxel (x,y,z) in the dense order (x fastest, then y, then z) of volume
  // files, checksums and the dense arrays of consumers.
  size_t index(int x, int y, int z) const {
    return (size_t(z) * size_t(dims_.y) + size_t(y)) * size_t(dims_.x) + size_t(x);
  }

  // --- reading (zero in unallocated bricks) ---
  float at(int x, int y, int z) const {
    const float* b = brickPointer(brickIndex(x, y, z));
    return b ? b[voxelInBrick(x, y, z)] : 0.0f;
  }
  // n voxels from `start` along `axis` (0 x, 1 y, 2 z) into out; the line must lie inside.
  void readLine(glm::ivec3 start, int axis, int n, float* out) const;
  // True when some voxel holds density (> 0); looks into allocated bricks only.
  bool hasDensity() const;
  // The whole grid in the dense order (sizes are checked: at most 2^31 voxels).
  std::vector<float> toDense() const;

  // --- writing (the caller marks what it touched dirty) ---
  // A reference to voxel (x,y,z), allocating its brick (zero-filled) if needed.
  float& voxelForWrite(int x, int y, int z) {
    return brickForWrite(brickIndex(x, y, z))[voxelInBrick(x, y, z)];
  }
  // The thesis's order-free merge: voxel = max(voxel, v). True when the voxel rose. A brick is
  // allocated only when it does.
  bool maxMerge(int x, int y, int z, float v) {
    if (!(v > at(x, y, z))) return false;
    voxelForWrite(x, y, z) = v;
    return true;
  }
  // n voxels from `in` along `axis` from `start`. Bricks are allocated only for segments holding
  // a non-zero bit pattern (writing zeros into an unallocated brick changes nothing).
  void writeLine(glm::ivec3 start, int axis, int n, const float* in);
  // Sets one voxel and marks it dirty.
  void set(int x, int y, int z, float v) {
    if (!isZeroBits(v) || brickPointer(brickIndex(x, y, z))) voxelForWrite(x, y, z) = v;
    markDirty({{x, y, z}, {x + 1, y + 1, z + 1}});
  }
  // Every voxel = v (v == +0 frees every brick) and the whole volume marked dirty.
  void fill(float v);
  // Copies a dense grid of voxelCount() floats (dense order) in, allocating only bricks holding
  // a non-zero bit pattern, and marks the whole volume dirty.
  void assignDense(const float* dense);

  // --- bricks ---
  glm::ivec3 brickDims() const { return brick_dims_; }
  size_t brickCount() const { return table_.size(); }
  // Voxels of brick `brick` inside the volume (edge bricks may be partial).
  VoxelBox brickBox(glm::ivec3 brick) const {
    const glm::ivec3 lo = brick * kBrickSize;
    return VoxelBox{lo, lo + kBrickSize}.intersect(bounds());
  }
  // The brick's 16³ voxels (x fastest) or nullptr when it is not allocated.
  const float* brick(glm::ivec3 b) const { return brickPointer(brickIndexOf(b)); }
  float* brickForWrite(glm::ivec3 b) { return brickForWrite(brickIndexOf(b)); }
  // Frees the brick when every voxel bit is zero (it then reads the same); marks nothing dirty,
  // since no value changes. True when freed.
  bool releaseEmptyBrick(glm::ivec3 b);
  size_t allocatedBricks() const { return allocated_; }
  // Coordinates of the allocated bricks, z-major then y then x (a fixed order).
  std::vector<glm::ivec3> allocatedBrickList() const;
  // Bytes held: allocated bricks plus the brick table.
  size_t memoryBytes() const;
  // This volume's bricks moved, without copying a voxel, into a new grid of `dims` over
  // [world_min, world_max]: brick b becomes brick b + brick_offset (how the sky grows around
  // what is painted, sky_extent.h). The new volume is marked dirty as a whole; this one is left
  // empty. std::invalid_argument when this volume's dims are not whole bricks or a brick would
  // land outside the new grid.
  Volume movedInto(glm::ivec3 dims, glm::vec3 world_min, glm::vec3 world_max,
                   glm::ivec3 brick_offset) &&;
  // Where this volume's contents came from when movedInto made it: the moved volume's
  // instanceId and generation at the move (nothing changed in between, since the move takes its
  // bricks as they were), its dims and the brick offset, and this volume's generation right
  // after the move (every change since is in dirtySince/changedBricksSince of it). A consumer
  // that had seen exactly (from_instance, from_generation) can shift what it holds by the offset
  // instead of starting over (VolumeRenderer::sync). Copies and moves keep it, as they keep the
  // generation and the change list it refers to; from_instance 0: not made by a move.
  struct Growth {
    uint64_t from_instance = 0;
    uint64_t from_generation = 0;
    glm::ivec3 from_dims{0};
    glm::ivec3 brick_offset{0};
    uint64_t generation = 0;
  };
  const Growth& growth() const { return growth_; }

  // --- changes ---
  // Records a change (clipped to bounds) and returns the new generation.
  uint64_t markDirty(const VoxelBox& box);
  uint64_t generation() const { return generation_; }
  // Union of every box marked after generation `since` (the whole volume if that is older
  // than the kept history).
  VoxelBox dirtySince(uint64_t since) const;
  // Bricks inside a box marked after generation `since`, in the fixed brick order; exact at any
  // age (each brick keeps the generation of the last change that touched it).
  std::vector<glm::ivec3> changedBricksSince(uint64_t since) const;

  // World <-> voxel coordinates. Voxel (i,j,k) covers [i,i+1) in continuous voxel space; its
  // centre is at i+0.5.
  glm::vec3 voxelSize() const { return (world_max_ - world_min_) / glm::vec3(dims_); }
  glm::vec3 worldToVoxel(glm::vec3 w) const { return (w - world_min_) / voxelSize(); }
  glm::vec3 voxelToWorld(glm::vec3 v) const { return world_min_ + v * voxelSize(); }

 private:
  static bool isZeroBits(float v) { return std::bit_cast<uint32_t>(v) == 0; }
  size_t brickIndexOf(glm::ivec3 b) const {
    return (size_t(b.z) * size_t(brick_dims_.y) + size_t(b.y)) * size_t(brick_dims_.x) +
           size_t(b.x);
  }
  size_t brickIndex(int x, int y, int z) const {
    return brickIndexOf({x >> kBrickShift, y >> kBrickShift, z >> kBrickShift});
  }
  static size_t voxelInBrick(int x, int y, int z) {
    constexpr int m = kBrickSize - 1;
    return (size_t(z & m) << (2 * kBrickShift)) | (size_t(y & m) << kBrickShift) | size_t(x & m);
  }
  const float* brickPointer(size_t i) const {
    return std::atomic_ref<float*>(const_cast<float*&>(table_[i])).load(std::memory_order_acquire);
  }
  float* brickForWrite(size_t i) {
    float* b = std::atomic_ref<float*>(table_[i]).load(std::memory_order_acquire);
    return b ? b : allocateBrick(i);
  }
  float* allocateBrick(size_t i);
  void freeAll();
  void copyBricksFrom(const Volume& o);

  glm::ivec3 dims_;
  glm::vec3 world_min_, world_max_;
  glm::ivec3 brick_dims_;
  std::vector<float*> table_;            // one per brick: its voxels or nullptr
  std::vector<uint64_t> brick_changed_;  // one per brick: generation of its last change
  size_t allocated_ = 0;
  std::unique_ptr<std::mutex> allocation_ = std::make_unique<std::mutex>();
  uint64_t generation_ = 0;
  uint64_t instance_id_;
  struct Change {
    uint64_t generation;
    VoxelBox box;
  };
  std::deque<Change> changes_;  // most recent last, bounded
  Growth growth_;
};

}  // namespace cb
