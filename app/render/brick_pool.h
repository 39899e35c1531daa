// The GPU copy of a sparse Volume and its light volume: a brick pool texture with an
// indirection table, after the bricks of GigaVoxels / NanoVDB-style sparse textures.
//
//  - Pool: one RGBA8 2D array texture of slots of kSlotTexels³ = 20³ texels (20 × 20 texels on
//    20 layers). The slot of brick b holds voxels 16b … 16b+19 on each axis: its own 16, the
//    first voxel of the next brick and an apron of kApron = 3 more (so a chunk of up to 4 ray
//    samples, looked up once, stays inside one slot); indices are clamped to the volume as a
//    dense texture's CLAMP_TO_EDGE would. A texel holds its voxel's density and transmittance
//    towards the light (r, g) and those of the voxel above it in z, the next layer's r and g
//    (b, a; the slot's last layer repeats its own). So one bilinear fetch reads all 8 voxels a
//    trilinear sample needs — 4 texels where a 3D RG8 texture's trilinear fetch gathered 8,
//    which llvmpipe's per-lane gathers are paid by — and the shader lerps in z. Twice the bytes
//    of an RG8 3D pool.
//  - Smoothed density: a companion RG16 2D array texture of the same size and slot layout
//    holding, per texel, the density smoothed over about 3 voxels (the mean of the 8-bit
//    densities of the 8 voxels diagonally next to it, ±1 on each axis) of its voxel and of the
//    voxel above it in z. A trilinear read of it is the mean of 8 trilinear density reads ±1
//    voxel apart (the filter commutes with trilinear interpolation): one read per step for the
//    iso-surface styles' inner surface (shaders/raycast.frag.glsl) instead of 8. 16 bits, because
//    that surface's line is drawn where the field's screen derivative says it crosses a level:
//    8-bit steps (and llvmpipe's 8-bit filtering) made flat terraces that broke the line into
//    dashes (cartoon islands on the gallery's s_curve 14 → 20 per 10,000 cloud pixels). A
//    slot's smoothed texels read voxels 16b − 1 … 16b + 20, so an edited brick c may reach the
//    slots of c + {−1,0,1}³.
//  - Indirection: one RGBA8 texel per brick (Volume::brickDims), read with nearest filtering,
//    holding the slot's coordinates in slots and a = 1; (0,0,0,0) is the empty slot (all density
//    0), shared by every brick without one. (RGBA8 rather than an integer texture: llvmpipe's
//    normalised fetch measured a little cheaper than texelFetch or a storage buffer.)
//
// Lookup rule (shaders/volume_pool.glsl): a voxel-space point p is sampled in the slot of brick
// b = ⌊(p − ½)/16⌋ (clamped to the bricks), its "cell" being [16b + ½, 16b + 16½) per axis.
// Trilinear filtering at p (the texture unit's bilinear in x and y, the shader's lerp in z) reads
// voxels ⌊p − ½⌋ and ⌊p − ½⌋ + 1, both within 16b … 16b+16 (… 16b+19 for the rest of a chunk),
// so a sample inside its slot gives exactly what the dense texture gave. Hence a brick needs a slot
// when any voxel it can read is non-zero, i.e. when one of the bricks b + {0,1}³ is allocated (this
// covers an empty brick whose high neighbour holds the density a sample within half a voxel of
// their face blends in). Every other brick reads the empty slot: zero density, which is what the
// dense texture held there (its transmittance is then never weighted: a sample of zero density is
// transparent, and an iso-surface is never hit there).
//
// Updates follow the bricks that changed: a changed density brick c refreshes the slots of
// c + {−1,0,1}³ (c − {0,1}³ read its density, and c + {0,1}³ its smoothed density; allocating or
// releasing them as the rule above now says) and a light box the slots whose voxels meet it.
// Given the box of voxels whose density changed, a slot is re-packed only where it reads them:
// its main texels when they hold one (voxels 16b … 16b + 19), else its smoothed companion alone
// when that reads one (16b − 1 … 16b + 20); a slot re-packed for its light alone re-packs its
// main texels (the companion holds density only).
// Released slots are reused; the pool grows (a slot column, row or layer at a time to a quarter
// more slots than needed, copied on the GPU with glCopyImageSubData) only when it runs out, so
// slots keep their coordinates and nothing is re-packed. A fresh volume (another one, or new dims)
// gets a pool of the size it needs: one that held a bigger cloud before is made anew, smaller.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "app/render/gl/gl.h"
#include "app/render/light_volume.h"
#include "app/volume/box.h"
#include "app/volume/volume.h"

namespace cb {

// How finely an update reports what rays read differently: texel by texel (each changed slot's
// old bytes read back and compared: the least to re-cast after a small edit), or each changed
// slot whole (nothing read back: for frames that re-cast all a change can show anyway, such as
// an animation's, which changes the whole cloud every frame).
enum class ChangeDetail { kTexels, kSlots };

class BrickPool {
 public:
  // Per axis: a brick, the first voxel of the next one and kApron more.
  static constexpr int kApron = 3;
  static constexpr int kSlotTexels = Volume::kBrickSize + 1 + kApron;
  // RGBA8 texels: density and transmittance of the texel's own voxel, then of the voxel above
  // it in z (the next layer's r and g).
  static constexpr size_t kTexelBytes = 4;
  static constexpr size_t kSlotBytes =
      size_t(kSlotTexels) * kSlotTexels * kSlotTexels * kTexelBytes;
  static_assert(kSlotTexels - Volume::kBrickSize == LightByteChanges::kLowVoxels);
  // The smoothed-density companion's RG16 texels: the texel's voxel and the one above it in z.
  static constexpr size_t kSmoothTexelBytes = 4;
  static constexpr size_t kSmoothSlotBytes =
      size_t(kSlotTexels) * kSlotTexels * kSlotTexels * kSmoothTexelBytes;

  struct UpdateStats {
    int slots_uploaded = 0;   // slots re-packed and uploaded
    int slots_added = 0;      // bricks that got a slot
    int slots_released = 0;   // bricks whose slot was freed
    int slots_unchanged = 0;  // re-packed but their bytes were what the slot held: not uploaded
    bool grew = false;        // the pool texture was reallocated (and copied) to hold more slots
    bool shrank = false;   // a fresh volume needed fewer slots: the texture was made anew, smaller
    double pack_ms = 0.0;  // CPU packing
    double upload_ms = 0.0;  // glTextureSubImage3D of slots and indirection, growth copies
  };

  BrickPool() = default;
  ~BrickPool();
  BrickPool(const BrickPool&) = delete;
  BrickPool& operator=(const BrickPool&) = delete;

  // A slot's changed texels are reported per block of this many texels on each axis (2³ blocks
  // a slot): one box around a slot's changes covers much that did not change (a stroke's edge,
  // a shadow's slanted front), and more blocks cost the mask more triangles than they save
  // pixels (`cloudbrush bench scale`, docs/render.md).
  static constexpr int kChangeBlockTexels = kSlotTexels / 2;
  // What one block of a slot's change can alter in an image, as voxel boxes (clamped to the
  // volume).
  struct SlotChange {
    glm::ivec3 brick{0};
    // The voxels whose texels in this block of the slot now hold other bytes (density or
    // transmittance): a sample reading none of them in this slot reads what it read. The whole
    // slot when it was released or the update was `fresh`.
    VoxelBox bytes;
    // The part of `bytes` a sample of non-zero density can read: texels whose density changed,
    // and texels whose transmittance changed with a texel of non-zero density among their 3³
    // neighbours in the slot (a trilinear sample's 8 texels are one 2³ cell of the slot; its
    // density is 0 exactly when all 8 densities are, and then its opacity is 0, so its light
    // weighs nothing). What the composited styles (thesis, physical) can show changed; the
    // iso-surface styles read the light off the march and need `bytes`. May be empty.
    VoxelBox weighted;
  };

  // Brings the pool up to date. With `fresh` (another volume or new dims) every slot is
  // reassigned from the allocated bricks; otherwise `changed_bricks` (Volume::changedBricksSince)
  // and the light say what to refresh: `light_bytes` (the bricks whose 8-bit light an incremental
  // sweep changed, sweepLightVolume) if given and not `all`, else `light_box` (the light voxels
  // recomputed, every slot meeting it re-packed). `light` must hold valid
  // transmittance for every voxel of the bricks next to allocated ones (LightVolume::at).
  // Needs a current GL 4.5 context.
  // `changes`, if given, receives every slot that reads differently now: a slot added, released,
  // or re-packed to bytes it did not hold (a 64-bit hash of each slot's bytes is kept: the light
  // box re-packs many slots whose 8-bit transmittance did not change, and those are neither
  // uploaded nor reported), with the texels that changed: a re-packed slot's old bytes are read
  // back from the pool texture (only for slots whose hash changed) and compared texel by texel.
  // `density_box`, if given, bounds the voxels of `changed_bricks` whose density changed
  // (Volume::dirtySince): only the slots reading one of them are re-packed (see above); without
  // it every slot around a changed brick is.
  // With `detail` kSlots a re-packed slot's change is its whole slot, nothing read back.
  UpdateStats update(const Volume& volume, const LightVolume& light, bool fresh,
                     const std::vector<glm::ivec3>& changed_bricks, const VoxelBox& light_box,
                     const LightByteChanges* light_bytes = nullptr,
                     std::vector<SlotChange>* changes = nullptr,
                     const VoxelBox* density_box = nullptr,
                     ChangeDetail detail = ChangeDetail::kTexels);

  // Follows a growth of the volume (Volume::movedInto): brick b's slot becomes brick
  // b + brick_offset's, in a table of `brick_dims` bricks. The slots stay where they are in the
  // pool texture (nothing is packed or copied); the indirection table is made anew at the new
  // size and uploaded. What the growth itself changes in the slots — the slots along the old edge,
  // whose texels past it repeated the edge's voxels and now read the grown sky, and the bricks
  // just outside it that now read an allocated brick — is for the next `update` to refresh: pass
  // it the allocated bricks on the old edge among `changed_bricks` (growthEdgeBricks).
  void followGrowth(glm::ivec3 brick_dims, glm::ivec3 brick_offset);

  GLuint poolTexture() const { return pool_texture_; }
  // The smoothed-density companion (RG16, the pool's size and slots); 0 until enableSmooth.
  GLuint smoothTexture() const { return smooth_texture_; }
  // The companion is made, and kept up to date by every update, only once a style that reads it
  // is drawn (the iso-surface styles' inner-surface search): it doubles the pool's bytes, which
  // the thesis and physical styles never read. Packs it for every slot held now (`volume`: the
  // one the pool was last updated from).
  void enableSmooth(const Volume& volume);
  bool smoothEnabled() const { return smooth_enabled_; }
  GLuint indirectionTexture() const { return indirection_texture_; }
  // The pool texture's size in texels (whole slots: 20 × its size in slots).
  glm::ivec3 poolTexels() const { return pool_texels_; }
  glm::ivec3 brickDims() const { return brick_dims_; }
  // Bricks holding a slot of their own (the empty slot not counted).
  size_t slotsInUse() const { return slots_in_use_; }
  // Slots the pool texture holds (including the empty slot and free ones).
  size_t slotCapacity() const { return slotCount(capacity_); }
  // The slot coordinates of brick b ((0,0,0): the empty slot).
  glm::u8vec4 slotOf(glm::ivec3 b) const { return slot_of_brick_[brickIndex(b)]; }
  // GL texture bytes: the pool with its smoothed-density companion (once enabled), and the
  // indirection table.
  size_t poolBytes() const {
    return size_t(pool_texels_.x) * size_t(pool_texels_.y) * size_t(pool_texels_.z) *
           (kTexelBytes + (smooth_enabled_ ? kSmoothTexelBytes : 0));
  }
  size_t indirectionBytes() const { return slot_of_brick_.size() * 4; }
  // CPU bytes of the tables (indirection copy, free list, marks, hashes) and the staging buffers.
  size_t tableBytes() const;

 private:
  size_t brickIndex(glm::ivec3 b) const {
    return (size_t(b.z) * size_t(brick_dims_.y) + size_t(b.y)) * size_t(brick_dims_.x) +
           size_t(b.x);
  }
  // A new indirection texture of `brick_dims` texels (uninitialised) in place of the one held.
  void makeIndirectionTexture(glm::ivec3 brick_dims);
  void resetTables(glm::ivec3 brick_dims);
  // Puts every slot but the empty one on the free list.
  void freeEverySlot();
  static size_t slotCount(glm::ivec3 slots) {
    return size_t(slots.x) * size_t(slots.y) * size_t(slots.z);
  }
  // What a pool is sized for when it must hold `needed` slots: a quarter more, because growing
  // copies the whole pool (so the strokes after a fresh volume or a growth rarely grow it).
  static size_t withHeadroom(size_t needed) { return needed + needed / 4; }
  // The pool size in slots for `needed` slots: `slots` grown one column, row or layer at a time
  // (the axis with the fewest first) until they fit; `full` when the limits stopped it short.
  glm::ivec3 slotsFor(glm::ivec3 slots, size_t needed, bool* full) const;
  // With every slot free (a fresh volume): remakes the pool texture at the size `slots` need if
  // that is smaller than it is. True if it did.
  bool fitFresh(size_t slots, UpdateStats* stats);
  // Makes room for at least `slots` slots in use (plus the empty slot); false if the GL limit
  // on 3D texture size is reached.
  bool reserve(size_t slots, UpdateStats* stats);
  // A 2D array texture of `texels` for slots (linear filtering, clamped); 0 when out of memory.
  static GLuint makeSlotTexture(GLenum format, glm::ivec3 texels);
  void uploadIndirection(const VoxelBox& bricks);
  // The parts of a slot to re-pack: its main texels (density and light) and its smoothed
  // companion.
  enum Part : uint8_t { kMainPart = 1, kSmoothPart = 2, kBothParts = 3 };
  struct Repack {
    glm::ivec3 brick;
    uint8_t parts;
  };
  // update()'s steps. The bricks whose slot may change (added, released or refreshed): those
  // whose slot reads an allocated (fresh) or changed brick, in a fixed z, y, x order, with the
  // parts of their slot that read a changed voxel (of `density_box`, when given).
  std::vector<Repack> slotCandidates(const Volume& volume, bool fresh,
                                     const std::vector<glm::ivec3>& changed_bricks,
                                     const VoxelBox* density_box);
  // Releases the slots no brick needs, gives slots to the bricks that now need one (growing
  // the pool), and lists the slots to re-pack.
  void assignSlots(const Volume& volume, bool fresh, const std::vector<Repack>& candidates,
                   std::vector<Repack>* upload, VoxelBox* indirection_changed,
                   std::vector<SlotChange>* changes, UpdateStats* stats);
  // Adds the slots that read light bytes which changed (their main texels).
  void addLightReaders(const Volume& volume, const VoxelBox& light_box,
                       const LightByteChanges* light_bytes, std::vector<Repack>* upload);
  // The staging buffers of a batch of `slots` slots (kept between updates; the companion's
  // only once enabled, else nullptr).
  struct StagingBuffers {
    uint8_t* main;
    uint16_t* smooth;
  };
  StagingBuffers staging(size_t slots);
  // Packs and uploads the slots' parts in batches, skipping those whose bytes did not change,
  // and reports what rays read differently (`changes`: texel by texel when `compare`, else
  // each changed slot whole: after a fresh update, every slot).
  void uploadSlots(const Volume& volume, const LightVolume& light, bool compare,
                   const std::vector<Repack>& to_upload, std::vector<SlotChange>* changes,
                   UpdateStats* stats);
  // A slot's bytes before and after an upload, for slotDifference.
  struct SlotCompare {
    glm::ivec3 brick{0};
    const uint8_t *before = nullptr, *now = nullptr;
    const uint16_t *smooth_before = nullptr, *smooth_now = nullptr;  // null: not compared
  };
  // What rays read in the slot of `brick` (at texel `at` of the pool) before its upload and
  // after, its parts re-packed into `main` and `smooth` as `parts` say; `added`: it read the
  // empty slot; `main_changed`/`smooth_changed`: the re-packed part's hash changed. Read back
  // from the pool (before the upload) into the batch's slot `s` of the compare buffers.
  SlotCompare slotBeforeAndNow(glm::ivec3 brick, glm::ivec3 at, uint8_t parts, bool added,
                               bool main_changed, bool smooth_changed, const uint8_t* main,
                               const uint16_t* smooth, size_t s);
  // What rays read differently in each compared slot, in their order (the slots compared in
  // parallel).
  void reportSlotChanges(const Volume& volume, const std::vector<SlotCompare>& compares,
                         std::vector<SlotChange>* changes) const;
  std::vector<uint8_t> compare_main_;     // per batch slot: the bytes before, the bytes held
  std::vector<uint16_t> compare_smooth_;  // per batch slot: the companion before

  glm::ivec3 brick_dims_{0};
  glm::ivec3 pool_texels_{0};               // pool texture size: capacity_ · kSlotTexels
  glm::ivec3 capacity_{0};                  // pool size in slots, pool_texels_ / kSlotTexels
  std::vector<glm::u8vec4> slot_of_brick_;  // per brick, as uploaded to the indirection table
  std::vector<glm::u8vec4> free_slots_;     // a stack
  std::vector<uint8_t> mark_;               // per brick, scratch for de-duplicating candidates
  std::vector<uint64_t> slot_hash_;         // per brick, hash of its slot's bytes (slotHash)
  std::vector<uint64_t> smooth_hash_;       // per brick, hash of its companion's bytes
  size_t slots_in_use_ = 0;
  GLuint pool_texture_ = 0, smooth_texture_ = 0, indirection_texture_ = 0;
  bool smooth_enabled_ = false;
  // The parts a slot holds: its main texels, and its companion once enabled.
  uint8_t allParts() const { return smooth_enabled_ ? kBothParts : kMainPart; }
  bool full_reported_ = false;
  std::unique_ptr<uint8_t[]> staging_main_;  // a batch's packed main texels (staging)
  std::unique_ptr<uint16_t[]> staging_smooth_;
  size_t staging_slots_ = 0;
};

// The allocated bricks of `grown` on the faces of the box a growth moved the old volume's bricks
// into (Volume::Growth: from_dims bricks at brick_offset) that lie inside the grown grid: the
// bricks whose slots (c − {0,1}³, BrickPool::update) the growth changes.
std::vector<glm::ivec3> growthEdgeBricks(const Volume& grown);

// Packs the slot of `brick` (BrickPool's layout: 20³ RGBA8 texels, x fastest; texel j on an axis
// is voxel min(16·b + j, dim − 1)): density clamped to [0,1] and the light's transmittance, both
// rounded to 8 bits, of the texel's voxel (bytes 0, 1) and of the texel above it in z (bytes 2,
// 3; the last layer's are its own). Reads transmittance only through LightVolume::at.
void packBrickSlot(const Volume& volume, const LightVolume& light, glm::ivec3 brick, uint8_t* out);

// Packs the smoothed-density companion of `brick`'s slot (20³ RG16 texels, x fastest, texel j on
// an axis at voxel 16·b + j): value 0 is smoothUnorm16 of the sum of the 8-bit densities of the 8
// voxels (±1, ±1, ±1) from the texel's voxel (indices clamped to the volume), value 1 that of
// the texel above it in z (the last layer repeats its own).
void packSmoothSlot(const Volume& volume, glm::ivec3 brick, uint16_t* out);

// The mean of 8 density bytes summing to `sum` (0 … 8·255) as a 16-bit unorm, rounded.
inline uint16_t smoothUnorm16(int sum) {
  return uint16_t((sum * 65535 + 1020) / 2040);
}

// A 64-bit hash of one packed slot (kSlotBytes), never 0 (0 marks "no slot").
uint64_t slotHash(const uint8_t* slot);

// The texels of two packed slots (kSlotBytes each) that differ: appends one SlotChange per
// block of BrickPool::kChangeBlockTexels³ texels holding a changed one, its boxes in texel
// coordinates of the slot (lo inclusive, hi exclusive; `weighted` judged by `now`'s densities)
// and `brick` left 0. Nothing when the slots are equal. A texel counts by its own bytes (0 and 1):
// bytes 2 and 3 repeat the next layer's, which counts for itself. With `smooth_before` and
// `smooth_now` (the companions, packSmoothSlot), a texel whose smoothed density (value 0) changed
// counts in `bytes` too (only the iso-surface styles read it).
void slotDifference(const uint8_t* before, const uint8_t* now,
                    std::vector<BrickPool::SlotChange>* out,
                    const uint16_t* smooth_before = nullptr, const uint16_t* smooth_now = nullptr);

}  // namespace cb
