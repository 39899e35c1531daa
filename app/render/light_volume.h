// The light volume of thesis §4.5 (Alg. 5): per voxel, the transmittance towards a directional
// sun, T = Π (1 − k·density) over unit steps from the voxel to the volume's edge along the light
// direction (app/scene/light.h). The shading stage turns it into the thesis's strength S(I) with
// I = 1 − T (see shaders/shade_thesis.glsl).
//
// Two ways to compute it, both free functions over the grid:
//  - sweepLightVolume: slice by slice along the light's major axis, starting at the light side.
//    Each voxel takes the (bilinearly interpolated) transmittance of the point one slice
//    upstream and attenuates it by its own voxel over that step: T(x) = (1 − k·d(x))^ℓ · T(x+u),
//    u = L / |L_major| (one slice towards the light), ℓ = |u| in voxels. O(voxels swept),
//    parallel. Alg. 5 starts its unit steps at the voxel itself, which weights the voxel's own
//    density by ½ more than the integral from its centre; to match, the stored T weights the own
//    voxel by (ℓ+1)/2 while the value passed downstream ("through") carries ℓ.
//  - marchLightReference: the straightforward per-voxel march of Alg. 5 (trilinear density at
//    x + i·L̂, i = 0, 1, …, until the point leaves the box). O(voxels × edge length); used by
//    tests and the benchmark as the reference.
//
// Sparse: the light volume is stored in the volume's 16³ bricks, and only where it
// differs from "fully lit, empty":
//  - `through` holds a brick wherever some voxel's passed-on value is not exactly 1 — the cloud
//    and its shadow across empty space. Elsewhere every voxel is exactly 1: a voxel with no
//    density whose upstream footprint is all 1 computes 1·(1 − w) + 1·w = 1 and (1 − k·0)^ℓ = 1
//    exactly (round to nearest, no FMA), so the sweep skips such 16×16 tiles and its cost follows
//    the painting and its shadow, not the sky's extent.
//  - `lit` holds T for the bricks the volume has allocated (where density may be non-zero). In
//    a brick without density T equals the passed-on value, so `through` (or 1) serves there.
//  - Neither is kept where the shadow falls on nothing: past the most downstream light brick of
//    each brick column along the sweep's axis (below the lowest cloud for a sun from above; a
//    column goes at least as deep as the columns its tiles read, so a stored tile never reads an
//    unstored one). The sweep reads only upstream, so those tiles are not swept at all
//    (`stored_slices`). An edit that allocates a brick further downstream sweeps the newly
//    stored tiles whole; an erase that lifts a column's lowest cloud frees them.
// After sweepLightVolume, `at` therefore equals the dense sweep's T at every voxel of the stored
// slices, which hold every brick the renderer reads; beyond them it reads 1.
// The renderer reads the "light bricks" (lightBrickList: the allocated bricks and their 26
// neighbours, which trilinear samples of non-zero density can reach); the reduced preview
// (reduced_light_sweep.h) stores only those and reads 1 elsewhere, where nothing reads it.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <vector>

#include <glm/glm.hpp>

#include "app/scene/light.h"
#include "app/volume/box.h"
#include "app/volume/volume.h"

namespace cb {

// A grid of optional 16³ float bricks (Volume's brick layout, x fastest); an absent brick reads
// as 1. Bricks are created by `create` from several threads at once (distinct bricks) while
// others read `get`; reset, release and copying belong to one thread.
class LightBricks {
 public:
  LightBricks() = default;
  LightBricks(const LightBricks& o);
  LightBricks& operator=(const LightBricks& o);
  LightBricks(LightBricks&& o) noexcept;
  LightBricks& operator=(LightBricks&& o) noexcept;
  ~LightBricks();

  // Frees every brick and sizes the table for `brick_dims` bricks.
  void reset(glm::ivec3 brick_dims);
  // The same, but keeps the bricks' memory for the next `create`s (a light change creates most
  // of them again; fresh pages cost more than the sweep's arithmetic); dropSpare frees the rest.
  void recycle(glm::ivec3 brick_dims);
  void dropSpare();
  // Re-indexes the table for `brick_dims` bricks, brick b becoming brick b + brick_offset (the
  // volume grew around it, Volume::movedInto): no brick is copied. Every brick must land inside.
  void shift(glm::ivec3 brick_dims, glm::ivec3 brick_offset);
  glm::ivec3 brickDims() const { return brick_dims_; }
  size_t brickIndex(glm::ivec3 b) const {
    return (size_t(b.z) * size_t(brick_dims_.y) + size_t(b.y)) * size_t(brick_dims_.x) +
           size_t(b.x);
  }
  const float* get(size_t i) const {
    return std::atomic_ref<float*>(const_cast<float*&>(table_[i])).load(std::memory_order_acquire);
  }
  float* getForWrite(size_t i) { return std::atomic_ref<float*>(table_[i]).load(); }
  // Creates brick i (absent) holding a copy of `init`'s 16³ values, or 1 everywhere.
  float* create(size_t i, const float* init = nullptr);
  void release(size_t i);
  size_t allocated() const { return allocated_.load(std::memory_order_relaxed); }
  size_t memoryBytes() const {
    return allocated() * Volume::kBrickBytes + table_.size() * sizeof(float*);
  }

 private:
  void freeAll();
  glm::ivec3 brick_dims_{0};
  std::vector<float*> table_;
  std::atomic<size_t> allocated_{0};
  std::vector<float*> spare_;  // recycled bricks, taken by create
  std::mutex spare_mutex_;
};

struct LightVolume {
  glm::ivec3 dims{0};
  glm::vec3 direction{0.0f};  // unit, voxel space, towards the light
  float extinction = -1.0f;   // k the volume was computed with (−1: matches no light)
  LightBricks lit;            // T of the bricks holding density (see the file comment)
  LightBricks through;        // passed-on values where they are not 1
  // Per brick column along the sweep's major axis (the two lateral brick axes, the one of smaller
  // memory stride fastest): how many slices, counted from the light side, store their light —
  // down to the column's most downstream light brick, and at least as deep as the columns its
  // sweep reads. Past it the shadow falls on nothing the renderer reads, so it is neither swept
  // nor stored (see the file comment).
  std::vector<int> stored_slices;
  // Per brick (LightBricks::brickIndex): 64-bit hashes of its 8-bit light as the GPU copy holds
  // it (unorm8 of `at`), one per part of the brick (part bit a: the voxels below
  // LightByteChanges::kLowVoxels on axis a, which the slot below reads too), kept by
  // sweepLightVolume while it reports LightByteChanges, so that a full sweep (a new light
  // direction) can name the bricks whose 8 bits changed instead of every brick; empty when not
  // known (anything else that writes the bricks clears it).
  using BrickHash = std::array<uint64_t, 8>;
  std::vector<BrickHash> byte_hash;

  bool matches(const Volume& volume, const Light& light) const;
  // T at voxel (x,y,z), 1 = fully lit: after sweepLightVolume exact in the stored slices (every
  // light brick, lightBrickList, lies in them) and 1 beyond; after a reduced preview exact only on
  // light bricks, 1 elsewhere. Nothing reads it where it reads 1 instead of the shadow.
  float at(int x, int y, int z) const {
    if (through.brickDims().x == 0) return 1.0f;
    constexpr int s = Volume::kBrickShift, m = Volume::kBrickSize - 1;
    const size_t i = through.brickIndex({x >> s, y >> s, z >> s});
    const size_t o = (size_t(z & m) << (2 * s)) | (size_t(y & m) << s) | size_t(x & m);
    if (const float* p = lit.get(i)) return p[o];
    if (const float* p = through.get(i)) return p[o];
    return 1.0f;
  }
  // T of n voxels from `start` along x (the row must lie inside the grid), as `at` gives them.
  void readRow(glm::ivec3 start, int n, float* out) const;
  // Brick `brick`'s 16³ T values (x fastest; voxels of an edge brick outside the grid read 1).
  // Never nullptr for a brick of the grid (a fully lit brick shares one brick of ones); nullptr
  // outside the grid or before the first sweep.
  const float* brickTransmittance(glm::ivec3 brick) const;
  // Bytes held: both brick sets, their tables, the stored depths and the byte hashes.
  size_t memoryBytes() const {
    return lit.memoryBytes() + through.memoryBytes() + stored_slices.size() * sizeof(int) +
           byte_hash.size() * sizeof(BrickHash);
  }
  // Every voxel's T in the volume's dense order (tests and tools; at most 2^31 voxels).
  std::vector<float> toDense() const;
};

// A value in [0, 1] as the GPU copy holds it (brick_pool.h): 8 bits, rounded to nearest, clamped.
// (No libm call: this runs for every packed or compared voxel.)
inline uint8_t unorm8(float v) {
  return uint8_t(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f);
}

// Which bricks' light a sweep changed as the renderer reads it: LightVolume::at rounded by unorm8.
struct LightByteChanges {
  // A brick's voxels v < kLowVoxels on an axis are also read by the brick-pool slot one brick
  // below on that axis (brick_pool.h: a slot holds its brick and the next brick's first voxels).
  static constexpr int kLowVoxels = 4;
  struct Brick {
    glm::ivec3 brick{0};
    // Bit δx + 2δy + 4δz (δ ∈ {0,1}³) set when the slot of brick − δ reads a changed voxel: some
    // changed voxel has v_i < kLowVoxels on every axis i with δ_i = 1. 0xFF: any may.
    uint8_t readers = 0;
  };
  bool all = false;           // a full recompute: any brick may have changed
  std::vector<Brick> bricks;  // otherwise the bricks where `at` may round differently now
};

// The light direction in voxel space (unit) for `light` shining on `volume`.
glm::vec3 lightDirectionInVoxels(const Volume& volume, const Light& light);

// The bricks whose T the renderer can read: the allocated bricks and their 26 neighbours (a
// trilinear sample of non-zero density reaches at most one voxel into a neighbour), in the
// volume's fixed brick order (z, then y, then x).
std::vector<glm::ivec3> lightBrickList(const Volume& volume);

// Brings `light_volume` up to date. If it was computed for another light, extinction or dims,
// recomputes everything; otherwise recomputes the voxels a density change in `dirty` reaches:
// the dirty box, then slice by slice away from the light the voxels whose upstream footprint saw
// any change in the previous slice (so the update stops where the edit's shadow no longer
// changes a bit, e.g. where it meets shadow that is already black). Returns the bounding box of
// the voxels rewritten (empty if none; the whole grid after a full recompute). `changes`, if
// given, receives the bricks whose 8-bit light changed (far fewer than the box holds: deep in
// the shadow the float values move but their 8 bits stay; brick_pool.h re-packs only those).
// A full recompute lists them too when the light volume's byte hashes are known from the sweep
// before (LightVolume::byte_hash: a new light leaves the 8 bits of the bricks in full light, or
// deep in shadow, as they were); else it reports `all`.
VoxelBox sweepLightVolume(LightVolume& light_volume, const Volume& volume, const Light& light,
                          const VoxelBox& dirty, LightByteChanges* changes = nullptr);

// Follows a growth of the volume (Volume::Growth: `grown` is the swept volume's bricks moved by
// `brick_offset`, the rest empty sky) without sweeping: light is a function of the density and
// the direction, growth only adds empty sky, and the sweep reads 1 outside the grid, so every
// stored value stays what it was; the bricks are re-indexed and each column's stored depth is
// carried over (counted from the light side, so it moves by the slices added there). Columns the
// grown sky now lets the shadow reach (past the old edge, and one brick further where the old
// edge cut a column short) are not stored yet: the next sweepLightVolume, incremental, sweeps
// them as newly stored (exactly what it does when an edit deepens a column), so it ends equal to
// a full sweep of the grown volume. A light volume that does not match `old_dims` (never swept,
// a reduced preview's dims) is reset instead: the next sweep is then a full one.
void shiftLightVolume(LightVolume& light_volume, glm::ivec3 old_dims, const Volume& grown,
                      glm::ivec3 brick_offset);

// The per-voxel reference march of Alg. 5 (slow: for tests and benchmarks). With z_step > 1 only
// the z slices z % z_step == 0 are computed (the others are set to -1), for timing and checking
// a sample of a large volume.
std::vector<float> marchLightReference(const Volume& volume, const Light& light, int z_step = 1);

// The thesis's shading strength S = 0.55 + cos(0.4 − I·π)/2.2 with I = 1 − T (§4.5.2, Fig. 4.19);
// the same formula as shaders/shade_thesis.glsl, for CPU checks.
float thesisStrength(float transmittance);

}  // namespace cb
