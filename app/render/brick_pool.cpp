#include "app/render/brick_pool.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>

#include "app/core/parallel_for.h"
#include "app/volume/brick_table_shift.h"

namespace cb {
namespace {

// The first pool: 3 × 3 × 1 slots of 20³ texels (the empty slot and 8 free ones, 281 KiB).
constexpr glm::ivec3 kInitialSlots{3, 3, 1};
// Slots packed into one staging buffer before their uploads (≈ 5 MB).
constexpr size_t kUploadBatch = 512;
// Slots whose changed texels are compared together (their bytes before kept meanwhile: 4 MB).
constexpr size_t kCompareChunk = 64;

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void resetUnpackState() {
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (GLenum p : {GL_UNPACK_ROW_LENGTH, GL_UNPACK_IMAGE_HEIGHT, GL_UNPACK_SKIP_PIXELS,
                   GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_IMAGES})
    glPixelStorei(p, 0);
}

bool valid(glm::ivec3 b, glm::ivec3 dims) {
  return glm::all(glm::greaterThanEqual(b, glm::ivec3(0))) && glm::all(glm::lessThan(b, dims));
}

// The empty slot's bytes: density 0, transmittance 1 (never weighted).
const std::vector<uint8_t>& emptySlotBytes() {
  static const std::vector<uint8_t> empty = [] {
    std::vector<uint8_t> e(BrickPool::kSlotBytes);
    for (size_t i = 0; i < e.size(); i += 4) {
      e[i] = e[i + 2] = 0;
      e[i + 1] = e[i + 3] = 255;
    }
    return e;
  }();
  return empty;
}

// The smoothed companion of the empty slot: density 0.
const std::vector<uint16_t>& emptySmoothSlot() {
  static const std::vector<uint16_t> empty(BrickPool::kSmoothSlotBytes / 2, 0);
  return empty;
}

// 64-bit words of `bytes` (a multiple of 8) mixed by multiply–xorshift, from `h`.
uint64_t mixWords(const uint8_t* bytes, size_t n, uint64_t h) {
  for (size_t i = 0; i < n; i += 8) {
    uint64_t w;
    std::memcpy(&w, bytes + i, 8);
    h = (h ^ w) * 0xBF58476D1CE4E5B9ull;
    h ^= h >> 31;
  }
  return h;
}

// The voxels a slot holds (voxels 16b … 16b + 19, clamped to the volume).
VoxelBox slotVoxels(glm::ivec3 b, const Volume& volume) {
  const glm::ivec3 lo = b * Volume::kBrickSize;
  return VoxelBox{lo, lo + BrickPool::kSlotTexels}.intersect(volume.bounds());
}

}  // namespace

void packBrickSlot(const Volume& volume, const LightVolume& light, glm::ivec3 brick, uint8_t* out) {
  constexpr int S = BrickPool::kSlotTexels;
  const glm::ivec3 dims = volume.dims();
  const glm::ivec3 lo = brick * Volume::kBrickSize;
  int ys[S], zs[S];
  for (int j = 0; j < S; ++j) {
    ys[j] = std::min(lo.y + j, dims.y - 1);
    zs[j] = std::min(lo.z + j, dims.z - 1);
  }
  const int nx = std::min(S, dims.x - lo.x);  // texels of a row inside the volume (≥ 1)
  float d[S], t[S];
  constexpr size_t T = BrickPool::kTexelBytes;
  const size_t row_bytes = T * size_t(S);
  for (int k = 0; k < S; ++k)
    for (int j = 0; j < S; ++j) {
      uint8_t* o = out + row_bytes * size_t(k * S + j);
      // Rows past the volume's edge repeat the last one inside (clamp to edge).
      if (k > 0 && zs[k] == zs[k - 1]) {
        std::memcpy(o, o - row_bytes * S, row_bytes);
        continue;
      }
      if (j > 0 && ys[j] == ys[j - 1]) {
        std::memcpy(o, o - row_bytes, row_bytes);
        continue;
      }
      const int y = ys[j], z = zs[k];
      volume.readLine({lo.x, y, z}, 0, nx, d);
      light.readRow({lo.x, y, z}, nx, t);  // a row at a time: cheaper than at() per voxel
      for (int i = 0; i < S; ++i) {
        o[T * i] = unorm8(d[std::min(i, nx - 1)]);
        o[T * i + 1] = unorm8(t[std::min(i, nx - 1)]);
      }
    }
  // Bytes 2 and 3: the next layer's own bytes (the last layer repeats its own: the chunk reads
  // it only with z weight 0).
  const size_t layer_bytes = row_bytes * S;
  for (int k = 0; k < S; ++k) {
    uint8_t* o = out + layer_bytes * size_t(k);
    const uint8_t* up = out + layer_bytes * size_t(std::min(k + 1, S - 1));
    for (size_t i = 0; i < layer_bytes; i += T) {
      o[i + 2] = up[i];
      o[i + 3] = up[i + 1];
    }
  }
}

void packSmoothSlot(const Volume& volume, glm::ivec3 brick, uint16_t* out) {
  constexpr int S = BrickPool::kSlotTexels;
  constexpr int R = S + 2;  // voxels 16b − 1 … 16b + 20 on each axis
  const glm::ivec3 dims = volume.dims();
  const glm::ivec3 lo = brick * Volume::kBrickSize - 1;
  // The 8-bit densities of those voxels (indices clamped to the volume), x fastest.
  static thread_local uint16_t d[R * R * R], sx[R * R * R], sy[R * R * R];
  const int x0 = std::max(lo.x, 0), x1 = std::min(lo.x + R, dims.x);  // the row inside
  float line[R];
  for (int k = 0; k < R; ++k)
    for (int j = 0; j < R; ++j) {
      const int y = std::clamp(lo.y + j, 0, dims.y - 1), z = std::clamp(lo.z + k, 0, dims.z - 1);
      volume.readLine({x0, y, z}, 0, x1 - x0, line);
      uint16_t* row = d + (k * R + j) * R;
      for (int i = 0; i < R; ++i) row[i] = unorm8(line[std::clamp(lo.x + i, x0, x1 - 1) - x0]);
    }
  // The 8 diagonal neighbours' sum, one axis at a time: v[i − 1] + v[i + 1] (at most 2040).
  for (int k = 0; k < R; ++k)
    for (int j = 0; j < R; ++j)
      for (int i = 1; i < R - 1; ++i) {
        const int at = (k * R + j) * R + i;
        sx[at] = d[at - 1] + d[at + 1];
      }
  for (int k = 0; k < R; ++k)
    for (int j = 1; j < R - 1; ++j)
      for (int i = 1; i < R - 1; ++i) {
        const int at = (k * R + j) * R + i;
        sy[at] = sx[at - R] + sx[at + R];
      }
  constexpr size_t T = 2;  // values a texel
  // Texels past the volume's edge repeat its last voxel's value (clamp to edge).
  const glm::ivec3 last = dims - 1 - (lo + 1);
  for (int k = 0; k < S; ++k)
    for (int j = 0; j < S; ++j)
      for (int i = 0; i < S; ++i) {
        const int at =
            ((std::min(k, last.z) + 1) * R + std::min(j, last.y) + 1) * R + std::min(i, last.x) + 1;
        out[T * size_t((k * S + j) * S + i)] = smoothUnorm16(sy[at - R * R] + sy[at + R * R]);
      }
  // Value 1: the next layer's value 0 (the last layer repeats its own).
  const size_t layer = size_t(S) * S;
  for (int k = 0; k < S; ++k) {
    uint16_t* o = out + T * layer * size_t(k);
    const uint16_t* up = out + T * layer * size_t(std::min(k + 1, S - 1));
    for (size_t i = 0; i < layer; ++i) o[T * i + 1] = up[T * i];
  }
}

uint64_t slotHash(const uint8_t* slot) {
  // 64-bit words mixed by multiply–xorshift (kSlotBytes = 16000 is a multiple of 8).
  static_assert(BrickPool::kSlotBytes % 8 == 0 && BrickPool::kSmoothSlotBytes % 8 == 0);
  const uint64_t h = mixWords(slot, BrickPool::kSlotBytes, 0x9E3779B97F4A7C15ull);
  return h ? h : 1;
}

void slotDifference(const uint8_t* before, const uint8_t* now,
                    std::vector<BrickPool::SlotChange>* out, const uint16_t* smooth_before,
                    const uint16_t* smooth_now) {
  constexpr int S = BrickPool::kSlotTexels;
  constexpr size_t N = size_t(S) * S * S;
  // near[i]: a texel of non-zero density among texel i's 3³ neighbours in the slot (a separable
  // dilation of the non-zero densities, one axis at a time).
  uint8_t near[N], scratch[N];
  constexpr size_t T = BrickPool::kTexelBytes;
  for (size_t i = 0; i < N; ++i) near[i] = now[T * i] != 0;
  const size_t strides[3] = {1, size_t(S), size_t(S) * S};
  for (int axis = 0; axis < 3; ++axis) {
    const size_t st = strides[axis];
    std::memcpy(scratch, near, N);
    size_t i = 0;
    for (int z = 0; z < S; ++z)
      for (int y = 0; y < S; ++y)
        for (int x = 0; x < S; ++x, ++i) {
          const int c = axis == 0 ? x : axis == 1 ? y : z;  // the texel's coordinate on the axis
          uint8_t v = scratch[i];
          if (c > 0) v |= scratch[i - st];
          if (c < S - 1) v |= scratch[i + st];
          near[i] = v;
        }
  }
  constexpr int B = BrickPool::kChangeBlockTexels, blocks = S / B;
  glm::ivec3 lo[blocks * blocks * blocks], hi[blocks * blocks * blocks];
  glm::ivec3 wlo[blocks * blocks * blocks], whi[blocks * blocks * blocks];
  for (int k = 0; k < blocks * blocks * blocks; ++k) {
    lo[k] = wlo[k] = glm::ivec3(S);
    hi[k] = whi[k] = glm::ivec3(-1);
  }
  size_t i = 0;
  for (int z = 0; z < S; ++z)
    for (int y = 0; y < S; ++y)
      for (int x = 0; x < S; ++x, ++i) {
        // A texel's own bytes (0 and 1); bytes 2 and 3 repeat the next layer's.
        const bool density = before[T * i] != now[T * i];
        const bool light = before[T * i + 1] != now[T * i + 1];
        const bool smooth = smooth_before && smooth_before[2 * i] != smooth_now[2 * i];
        if (!density && !light && !smooth) continue;
        const glm::ivec3 t(x, y, z);
        const int k = (z / B * blocks + y / B) * blocks + x / B;
        lo[k] = glm::min(lo[k], t);
        hi[k] = glm::max(hi[k], t);
        if (density || near[i]) {
          wlo[k] = glm::min(wlo[k], t);
          whi[k] = glm::max(whi[k], t);
        }
      }
  for (int k = 0; k < blocks * blocks * blocks; ++k)
    if (hi[k].x >= 0)
      out->push_back({glm::ivec3(0), VoxelBox{lo[k], hi[k] + 1},
                      whi[k].x >= 0 ? VoxelBox{wlo[k], whi[k] + 1} : VoxelBox{}});
}

BrickPool::~BrickPool() {
  if (pool_texture_) glDeleteTextures(1, &pool_texture_);
  if (smooth_texture_) glDeleteTextures(1, &smooth_texture_);
  if (indirection_texture_) glDeleteTextures(1, &indirection_texture_);
}

size_t BrickPool::tableBytes() const {
  return slot_of_brick_.capacity() * sizeof(glm::u8vec4) +
         free_slots_.capacity() * sizeof(glm::u8vec4) + mark_.capacity() +
         (slot_hash_.capacity() + smooth_hash_.capacity()) * sizeof(uint64_t) +
         staging_slots_ * (kSlotBytes + (staging_smooth_ ? kSmoothSlotBytes : 0)) +
         compare_main_.capacity() + compare_smooth_.capacity() * sizeof(uint16_t);
}

void BrickPool::makeIndirectionTexture(glm::ivec3 brick_dims) {
  if (indirection_texture_) glDeleteTextures(1, &indirection_texture_);
  glCreateTextures(GL_TEXTURE_3D, 1, &indirection_texture_);
  glTextureStorage3D(indirection_texture_, 1, GL_RGBA8, brick_dims.x, brick_dims.y, brick_dims.z);
  glTextureParameteri(indirection_texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(indirection_texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  brick_dims_ = brick_dims;
}

void BrickPool::resetTables(glm::ivec3 brick_dims) {
  if (brick_dims != brick_dims_ || !indirection_texture_) makeIndirectionTexture(brick_dims);
  const size_t bricks = size_t(brick_dims.x) * brick_dims.y * brick_dims.z;
  slot_of_brick_.assign(bricks, glm::u8vec4(0));
  mark_.assign(bricks, 0);
  slot_hash_.assign(bricks, 0);
  smooth_hash_.assign(bricks, 0);
  slots_in_use_ = 0;
  if (!pool_texture_) {
    capacity_ = glm::ivec3(0);
    UpdateStats ignored;
    reserve(0, &ignored);
  }
  freeEverySlot();
}

void BrickPool::freeEverySlot() {
  // Every slot but the empty one is free (popped from the back: low coordinates first).
  free_slots_.clear();
  for (int z = capacity_.z - 1; z >= 0; --z)
    for (int y = capacity_.y - 1; y >= 0; --y)
      for (int x = capacity_.x - 1; x >= 0; --x)
        if (x || y || z) free_slots_.push_back(glm::u8vec4(x, y, z, 1));
}

glm::ivec3 BrickPool::slotsFor(glm::ivec3 slots, size_t needed, bool* full) const {
  GLint max_size = 0, max_layers = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
  // At most 255 slots per axis (slot coordinates are 8-bit) and what GL allows.
  const int across = std::min(255, max_size / kSlotTexels);
  const glm::ivec3 most(across, across, std::min(255, max_layers / kSlotTexels));
  *full = false;
  while (slotCount(slots) < needed) {
    // One more slot column, row or layer on the axis with the fewest (the pool stays near a
    // cube, so each step adds few slots beyond what is needed).
    int axis = -1;
    for (int a = 0; a < 3; ++a)
      if (slots[a] < most[a] && (axis < 0 || slots[a] < slots[axis])) axis = a;
    if (axis < 0) {
      *full = true;
      break;
    }
    ++slots[axis];
  }
  return slots;
}

bool BrickPool::fitFresh(size_t slots, UpdateStats* stats) {
  bool full = false;
  const glm::ivec3 fitted = slotsFor(kInitialSlots, withHeadroom(slots + 1), &full);
  if (!pool_texture_ || slotCount(fitted) >= slotCapacity()) return false;
  glDeleteTextures(1, &pool_texture_);
  glDeleteTextures(1, &smooth_texture_);
  pool_texture_ = smooth_texture_ = 0;
  capacity_ = glm::ivec3(0);
  reserve(slots, stats);
  freeEverySlot();
  return true;
}

GLuint BrickPool::makeSlotTexture(GLenum format, glm::ivec3 texels) {
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &texture);
  glTextureStorage3D(texture, 1, format, texels.x, texels.y, texels.z);
  if (glGetError() == GL_OUT_OF_MEMORY) {
    glDeleteTextures(1, &texture);
    return 0;
  }
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T})
    glTextureParameteri(texture, wrap, GL_CLAMP_TO_EDGE);
  return texture;
}

bool BrickPool::reserve(size_t slots, UpdateStats* stats) {
  const size_t needed = slots + 1;  // and the empty slot
  if (pool_texture_ && slotCapacity() >= needed) return true;
  bool full = false;
  const glm::ivec3 cap =
      slotsFor(pool_texture_ ? capacity_ : kInitialSlots, withHeadroom(needed), &full);
  if (slotCount(cap) < needed && !full_reported_) {
    std::fprintf(stderr,
                 "cloudbrush: render: the brick pool is full (%zu slots needed, at most %zu fit "
                 "in a texture of %d x %d x %d slots): bricks beyond it show empty\n",
                 needed, slotCount(cap), cap.x, cap.y, cap.z);
    full_reported_ = true;
  }
  if (pool_texture_ && cap == capacity_) return false;
  const glm::ivec3 texels = cap * kSlotTexels;
  const GLuint texture = makeSlotTexture(GL_RGBA8, texels);
  const GLuint smooth = texture && smooth_enabled_ ? makeSlotTexture(GL_RG16, texels) : 0;
  if (!texture || (smooth_enabled_ && !smooth)) {
    if (texture) glDeleteTextures(1, &texture);
    std::fprintf(stderr, "cloudbrush: render: out of memory growing the brick pool to %zu bytes\n",
                 slotCount(cap) * (kSlotBytes + (smooth_enabled_ ? kSmoothSlotBytes : 0)));
    return false;
  }
  if (pool_texture_) {
    // Slots keep their coordinates: copy the old pool and its companion into the corner of the
    // new ones (on the GPU, nothing re-packed) and free the slots that are new.
    const glm::ivec3 old = pool_texels_;
    glCopyImageSubData(pool_texture_, GL_TEXTURE_2D_ARRAY, 0, 0, 0, 0, texture, GL_TEXTURE_2D_ARRAY,
                       0, 0, 0, 0, old.x, old.y, old.z);
    if (smooth)
      glCopyImageSubData(smooth_texture_, GL_TEXTURE_2D_ARRAY, 0, 0, 0, 0, smooth,
                         GL_TEXTURE_2D_ARRAY, 0, 0, 0, 0, old.x, old.y, old.z);
    glDeleteTextures(1, &pool_texture_);
    if (smooth_texture_) glDeleteTextures(1, &smooth_texture_);
    std::vector<glm::u8vec4> added;
    for (int z = cap.z - 1; z >= 0; --z)
      for (int y = cap.y - 1; y >= 0; --y)
        for (int x = cap.x - 1; x >= 0; --x)
          if (x >= capacity_.x || y >= capacity_.y || z >= capacity_.z)
            added.push_back(glm::u8vec4(x, y, z, 1));
    free_slots_.insert(free_slots_.begin(), added.begin(), added.end());
    stats->grew = true;
  } else {
    resetUnpackState();
    glTextureSubImage3D(texture, 0, 0, 0, 0, kSlotTexels, kSlotTexels, kSlotTexels, GL_RGBA,
                        GL_UNSIGNED_BYTE, emptySlotBytes().data());
    if (smooth)
      glTextureSubImage3D(smooth, 0, 0, 0, 0, kSlotTexels, kSlotTexels, kSlotTexels, GL_RG,
                          GL_UNSIGNED_SHORT, emptySmoothSlot().data());
  }
  pool_texture_ = texture;
  smooth_texture_ = smooth;
  pool_texels_ = texels;
  capacity_ = cap;
  return slotCount(cap) >= needed;
}

void BrickPool::enableSmooth(const Volume& volume) {
  if (smooth_enabled_) return;
  smooth_enabled_ = true;
  if (!pool_texture_) return;  // made with the pool
  smooth_texture_ = makeSlotTexture(GL_RG16, pool_texels_);
  if (!smooth_texture_) {
    std::fprintf(stderr,
                 "cloudbrush: render: out of memory making the brick pool's smoothed companion "
                 "(%zu bytes)\n",
                 slotCapacity() * kSmoothSlotBytes);
    smooth_enabled_ = false;
    return;
  }
  resetUnpackState();
  glTextureSubImage3D(smooth_texture_, 0, 0, 0, 0, kSlotTexels, kSlotTexels, kSlotTexels, GL_RG,
                      GL_UNSIGNED_SHORT, emptySmoothSlot().data());
  std::vector<uint16_t> smoothed(kSmoothSlotBytes / 2);
  const glm::ivec3 bd = brick_dims_;
  for (int z = 0; z < bd.z; ++z)
    for (int y = 0; y < bd.y; ++y)
      for (int x = 0; x < bd.x; ++x) {
        const glm::ivec3 b(x, y, z);
        const size_t i = brickIndex(b);
        if (!slot_of_brick_[i].w) continue;
        packSmoothSlot(volume, b, smoothed.data());
        smooth_hash_[i] =
            mixWords(reinterpret_cast<const uint8_t*>(smoothed.data()), kSmoothSlotBytes, 0) | 1;
        const glm::ivec3 at = glm::ivec3(slot_of_brick_[i]) * kSlotTexels;
        glTextureSubImage3D(smooth_texture_, 0, at.x, at.y, at.z, kSlotTexels, kSlotTexels,
                            kSlotTexels, GL_RG, GL_UNSIGNED_SHORT, smoothed.data());
      }
}

void BrickPool::followGrowth(glm::ivec3 brick_dims, glm::ivec3 brick_offset) {
  slot_of_brick_ = shiftedBrickTable(slot_of_brick_, brick_dims_, brick_dims, brick_offset);
  slot_hash_ = shiftedBrickTable(slot_hash_, brick_dims_, brick_dims, brick_offset);
  smooth_hash_ = shiftedBrickTable(smooth_hash_, brick_dims_, brick_dims, brick_offset);
  mark_.assign(slot_of_brick_.size(), 0);
  makeIndirectionTexture(brick_dims);
  uploadIndirection({glm::ivec3(0), brick_dims});
}

std::vector<glm::ivec3> growthEdgeBricks(const Volume& grown) {
  const Volume::Growth& g = grown.growth();
  const glm::ivec3 bd = grown.brickDims();
  const glm::ivec3 lo = g.brick_offset, hi = g.brick_offset + g.from_dims / Volume::kBrickSize;
  std::vector<glm::ivec3> edge;
  for (const glm::ivec3 b : grown.allocatedBrickList()) {
    bool on_edge = false;
    for (int a = 0; a < 3; ++a)
      on_edge |= (b[a] == lo[a] && lo[a] > 0) || (b[a] == hi[a] - 1 && hi[a] < bd[a]);
    if (on_edge) edge.push_back(b);
  }
  return edge;
}

void BrickPool::uploadIndirection(const VoxelBox& bricks) {
  if (bricks.empty()) return;
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, brick_dims_.x);
  glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, brick_dims_.y);
  glPixelStorei(GL_UNPACK_SKIP_PIXELS, bricks.lo.x);
  glPixelStorei(GL_UNPACK_SKIP_ROWS, bricks.lo.y);
  glPixelStorei(GL_UNPACK_SKIP_IMAGES, bricks.lo.z);
  const glm::ivec3 size = bricks.hi - bricks.lo;
  glTextureSubImage3D(indirection_texture_, 0, bricks.lo.x, bricks.lo.y, bricks.lo.z, size.x,
                      size.y, size.z, GL_RGBA, GL_UNSIGNED_BYTE, slot_of_brick_.data());
  resetUnpackState();
}

std::vector<BrickPool::Repack> BrickPool::slotCandidates(
    const Volume& volume, bool fresh, const std::vector<glm::ivec3>& changed_bricks,
    const VoxelBox* density_box) {
  const glm::ivec3 bd = brick_dims_;
  // Candidates: bricks whose slot may have to change (be added, released or refreshed); mark_
  // holds kCandidate and the parts to re-pack.
  constexpr uint8_t kCandidate = 4;
  std::vector<glm::ivec3> bricks;
  auto addCandidatesAround = [&](glm::ivec3 c) {
    // The voxels of c whose density changed (all of them without a box).
    const glm::ivec3 c0 = c * Volume::kBrickSize;
    VoxelBox changed{c0, c0 + Volume::kBrickSize};
    if (density_box && !fresh) changed = changed.intersect(*density_box);
    // Slot b reads bricks b + {0,1}³ and its smoothed companion b + {−1,0,1}³, so brick c is
    // read by the slots of c + {−1,0,1}³: their main texels when voxels 16b … 16b + 19 meet
    // the changed ones, their companion when 16b − 1 … 16b + 20 do (indices clamped to the
    // volume stay within those, the changed voxels being inside it).
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const glm::ivec3 b = c + glm::ivec3(dx, dy, dz);
          if (!valid(b, bd)) continue;
          const glm::ivec3 lo = b * Volume::kBrickSize;
          const VoxelBox main{lo, lo + kSlotTexels};
          uint8_t parts = 0;
          if (!main.intersect(changed).empty())
            parts = allParts();
          else if (smooth_enabled_ && !main.grow(1).intersect(changed).empty())
            parts = kSmoothPart;
          uint8_t& m = mark_[brickIndex(b)];
          if (!m) bricks.push_back(b);
          m |= kCandidate | parts;
        }
  };
  if (fresh)
    for (glm::ivec3 a : volume.allocatedBrickList()) addCandidatesAround(a);
  else
    for (glm::ivec3 c : changed_bricks) addCandidatesAround(c);
  // A fixed order (z, y, x) so slots are handed out the same way for the same changes.
  std::sort(bricks.begin(), bricks.end(), [](glm::ivec3 a, glm::ivec3 b) {
    return a.z != b.z ? a.z < b.z : a.y != b.y ? a.y < b.y : a.x < b.x;
  });
  std::vector<Repack> candidates;
  candidates.reserve(bricks.size());
  for (glm::ivec3 b : bricks) {
    uint8_t& m = mark_[brickIndex(b)];
    candidates.push_back({b, uint8_t(m & kBothParts)});
    m = 0;
  }
  return candidates;
}

void BrickPool::assignSlots(const Volume& volume, bool fresh, const std::vector<Repack>& candidates,
                            std::vector<Repack>* upload, VoxelBox* indirection_changed,
                            std::vector<SlotChange>* changes, UpdateStats* stats) {
  const glm::ivec3 bd = brick_dims_;
  UpdateStats& st = *stats;
  std::vector<Repack>& to_upload = *upload;
  auto needsSlot = [&](glm::ivec3 b) {
    for (int dz = 0; dz <= 1; ++dz)
      for (int dy = 0; dy <= 1; ++dy)
        for (int dx = 0; dx <= 1; ++dx) {
          const glm::ivec3 n = b + glm::ivec3(dx, dy, dz);
          if (valid(n, bd) && volume.brick(n)) return true;
        }
    return false;
  };
  std::vector<glm::ivec3> to_add;
  for (const auto [b, parts] : candidates) {
    const size_t i = brickIndex(b);
    const bool has = slot_of_brick_[i].w != 0;
    const bool needs = needsSlot(b);
    if (needs && !has) {
      to_add.push_back(b);
    } else if (!needs && has) {
      free_slots_.push_back(slot_of_brick_[i]);
      slot_of_brick_[i] = glm::u8vec4(0);
      slot_hash_[i] = smooth_hash_[i] = 0;
      if (changes) {
        const VoxelBox whole = slotVoxels(b, volume);
        changes->push_back({b, whole, whole});
      }
      --slots_in_use_;
      ++st.slots_released;
      *indirection_changed = indirection_changed->unite({b, b + 1});
    } else if (needs && parts) {
      to_upload.push_back({b, parts});
    }
  }
  // A fresh volume gets a pool sized for it: the texture shrinks when this volume needs fewer
  // slots than earlier ones did (nothing is in it yet to copy), so the pool does not stay at the
  // largest cloud's size for good (a kiosk resets to an empty sky between visitors).
  if (fresh) st.shrank = fitFresh(to_add.size(), &st);
  if (!to_add.empty() && free_slots_.size() < to_add.size())
    reserve(slots_in_use_ + to_add.size(), &st);
  for (glm::ivec3 b : to_add) {
    if (free_slots_.empty()) break;  // the pool is full (reported by reserve)
    const size_t i = brickIndex(b);
    slot_of_brick_[i] = free_slots_.back();
    free_slots_.pop_back();
    ++slots_in_use_;
    ++st.slots_added;
    *indirection_changed = indirection_changed->unite({b, b + 1});
    to_upload.push_back({b, allParts()});
  }
}

void BrickPool::addLightReaders(const Volume& volume, const VoxelBox& light_box,
                                const LightByteChanges* light_bytes, std::vector<Repack>* upload) {
  const glm::ivec3 bd = brick_dims_;
  std::vector<Repack>& to_upload = *upload;
  // The light: the slots reading a voxel whose 8-bit light changed (of c − {0,1}³ for each such
  // brick c, those its `readers` name); without that list, those whose voxels 16b … 16b +
  // kSlotTexels − 1 meet the light box. Their main texels are re-packed; mark_: 1 queued with
  // them, 2 queued for the companion alone, 3 the same now needing them too.
  const VoxelBox lb = light_box.intersect(volume.bounds());
  const bool by_bytes = light_bytes && !light_bytes->all;
  if (slots_in_use_ == 0 || (!by_bytes && lb.empty())) return;
  for (const Repack& r : to_upload) mark_[brickIndex(r.brick)] = r.parts & kMainPart ? 1 : 2;
  const size_t queued = to_upload.size();
  auto add = [&](glm::ivec3 b) {
    const size_t i = brickIndex(b);
    if (!slot_of_brick_[i].w) return;
    if (mark_[i] == 0) {
      mark_[i] = 1;
      to_upload.push_back({b, kMainPart});
    } else if (mark_[i] == 2) {
      mark_[i] = 3;
    }
  };
  if (by_bytes) {
    for (const LightByteChanges::Brick& c : light_bytes->bricks)
      for (int n = 0; n < 8; ++n) {
        const glm::ivec3 b = c.brick - glm::ivec3(n & 1, (n >> 1) & 1, n >> 2);
        if (c.readers >> n & 1 && valid(b, bd)) add(b);
      }
  } else {
    const glm::ivec3 blo = glm::max(
        (lb.lo - (kSlotTexels - Volume::kBrickSize)) >> Volume::kBrickShift, glm::ivec3(0));
    const glm::ivec3 bhi = (lb.hi - 1) >> Volume::kBrickShift;
    for (int z = blo.z; z <= bhi.z; ++z)
      for (int y = blo.y; y <= bhi.y; ++y)
        for (int x = blo.x; x <= bhi.x; ++x) add({x, y, z});
  }
  for (size_t k = 0; k < to_upload.size(); ++k) {
    uint8_t& m = mark_[brickIndex(to_upload[k].brick)];
    if (k < queued && m == 3) to_upload[k].parts |= kMainPart;
    m = 0;
  }
}

BrickPool::SlotCompare BrickPool::slotBeforeAndNow(glm::ivec3 b, glm::ivec3 at, uint8_t parts,
                                                   bool added, bool main_changed,
                                                   bool smooth_changed, const uint8_t* main,
                                                   const uint16_t* smooth, size_t s) {
  constexpr size_t kSmoothValues = kSmoothSlotBytes / 2;
  // What rays read there before: the empty slot for an added brick, else the slot's bytes, read
  // back from the pool for a part whose hash changed. A part not re-packed reads as before (the
  // main texels are read back when the companion changed: slotDifference weighs by density).
  SlotCompare c;
  c.brick = b;
  c.before = emptySlotBytes().data();
  const uint16_t* old_smooth = emptySmoothSlot().data();
  auto readMain = [&](uint8_t* into) {
    // Rows of 80 bytes: tight under any pack alignment (the project sets no other pack state).
    glGetTextureSubImage(pool_texture_, 0, at.x, at.y, at.z, kSlotTexels, kSlotTexels, kSlotTexels,
                         GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(kSlotBytes), into);
    return into;
  };
  uint8_t* const before = compare_main_.data() + s * 2 * kSlotBytes;
  if (!(parts & kMainPart)) main = readMain(before + kSlotBytes);
  if (!(parts & kSmoothPart)) smooth = nullptr;  // unchanged or not held: not compared
  if (!added) {
    c.before = main_changed ? readMain(before) : main;
    old_smooth = smooth;
    if (smooth && smooth_changed) {
      uint16_t* into = compare_smooth_.data() + s * kSmoothValues;
      glGetTextureSubImage(smooth_texture_, 0, at.x, at.y, at.z, kSlotTexels, kSlotTexels,
                           kSlotTexels, GL_RG, GL_UNSIGNED_SHORT, GLsizei(kSmoothSlotBytes), into);
      old_smooth = into;
    }
  }
  c.now = main;
  c.smooth_now = smooth;
  c.smooth_before = smooth ? old_smooth : nullptr;
  return c;
}

void BrickPool::reportSlotChanges(const Volume& volume, const std::vector<SlotCompare>& compares,
                                  std::vector<SlotChange>* changes) const {
  std::vector<std::vector<SlotChange>> per_slot(compares.size());
  parallelFor(compares.size(), 8, [&](size_t, size_t k0, size_t k1) {
    for (size_t k = k0; k < k1; ++k) {
      const SlotCompare& c = compares[k];
      slotDifference(c.before, c.now, &per_slot[k], c.smooth_before, c.smooth_now);
      // Texels to voxels: texel j is voxel 16b + j (those past the volume's edge repeat its
      // last voxel, which then changed too).
      const glm::ivec3 lo = c.brick * Volume::kBrickSize;
      auto toVoxels = [&](const VoxelBox& t) {
        return t.empty() ? t : VoxelBox{lo + t.lo, lo + t.hi}.intersect(volume.bounds());
      };
      for (SlotChange& change : per_slot[k])
        change = {c.brick, toVoxels(change.bytes), toVoxels(change.weighted)};
    }
  });
  for (const std::vector<SlotChange>& slot : per_slot)
    changes->insert(changes->end(), slot.begin(), slot.end());
}

BrickPool::StagingBuffers BrickPool::staging(size_t slots) {
  if (staging_slots_ < slots) {
    staging_main_.reset(new uint8_t[slots * kSlotBytes]);  // not zeroed: every byte is packed
    staging_smooth_.reset();
    staging_slots_ = slots;
  }
  if (smooth_enabled_ && !staging_smooth_)
    staging_smooth_.reset(new uint16_t[staging_slots_ * (kSmoothSlotBytes / 2)]);
  return {staging_main_.get(), staging_smooth_.get()};
}

void BrickPool::uploadSlots(const Volume& volume, const LightVolume& light, bool compare,
                            const std::vector<Repack>& to_upload, std::vector<SlotChange>* changes,
                            UpdateStats* stats) {
  UpdateStats& st = *stats;
  auto t0 = std::chrono::steady_clock::now();
  resetUnpackState();
  constexpr size_t kSmoothValues = kSmoothSlotBytes / 2;
  for (size_t first = 0; first < to_upload.size(); first += kUploadBatch) {
    const size_t n = std::min(kUploadBatch, to_upload.size() - first);
    t0 = std::chrono::steady_clock::now();
    // The batch's packed main texels and companions, in buffers kept from one update to the
    // next: a fresh 8 MB buffer a sync cost its page faults and zero-fill (a light change
    // re-packs about 2,300 slots: ~18 % of its CPU, docs/bench.md).
    const StagingBuffers buffers = staging(n);
    uint8_t* const staging = buffers.main;
    uint16_t* const smooth = buffers.smooth;
    // Per slot: which re-packed parts hold other bytes than the slot did (by their hashes; the
    // slot of an added brick held nothing: hash 0).
    enum : uint8_t { kMainChanged = 1, kSmoothChanged = 2, kAdded = 4 };
    std::vector<uint8_t> state(n, 0);
    // Small batches on the calling thread: waking workers costs more than a few slots.
    parallelFor(n, n < 16 ? n : 4, [&](size_t, size_t s0, size_t s1) {
      for (size_t s = s0; s < s1; ++s) {
        const auto [b, parts] = to_upload[first + s];
        const size_t i = brickIndex(b);
        uint8_t* main = staging + s * kSlotBytes;
        uint16_t* smoothed = smooth ? smooth + s * kSmoothValues : nullptr;
        if (slot_hash_[i] == 0) state[s] |= kAdded;
        if (parts & kMainPart) {
          packBrickSlot(volume, light, b, main);
          const uint64_t h = slotHash(main);
          if (h != slot_hash_[i]) state[s] |= kMainChanged;
          slot_hash_[i] = h;
        }
        if (parts & kSmoothPart) {
          packSmoothSlot(volume, b, smoothed);
          const uint64_t h =
              mixWords(reinterpret_cast<const uint8_t*>(smoothed), kSmoothSlotBytes, 0) | 1;
          if (h != smooth_hash_[i]) state[s] |= kSmoothChanged;
          smooth_hash_[i] = h;
        }
      }
    });
    st.pack_ms += msSince(t0);
    t0 = std::chrono::steady_clock::now();
    // The bytes read back for up to kCompareChunk slots (sized before: the compares point into
    // them), compared in parallel when the chunk is full and at the batch's end.
    std::vector<SlotCompare> compares;
    if (changes && compare) {
      compare_main_.resize(kCompareChunk * 2 * kSlotBytes);
      if (smooth) compare_smooth_.resize(kCompareChunk * kSmoothValues);
    }
    for (size_t s = 0; s < n; ++s) {
      if (state[s] == 0) {
        ++st.slots_unchanged;
        continue;
      }
      const auto [b, parts] = to_upload[first + s];
      const glm::ivec3 at = glm::ivec3(slot_of_brick_[brickIndex(b)]) * kSlotTexels;
      const uint8_t* main = staging + s * kSlotBytes;
      const uint16_t* smoothed = smooth ? smooth + s * kSmoothValues : nullptr;
      if (changes && !compare) {
        // Everything is new (the renderer starts its frames over), or the caller re-casts all a
        // changed slot can show anyway: the whole slot, no compare.
        const VoxelBox whole = slotVoxels(b, volume);
        changes->push_back({b, whole, whole});
      } else if (changes) {
        compares.push_back(slotBeforeAndNow(b, at, parts, state[s] & kAdded,
                                            state[s] & kMainChanged, state[s] & kSmoothChanged,
                                            main, smoothed, compares.size()));
        if (compares.size() == kCompareChunk) {
          reportSlotChanges(volume, compares, changes);
          compares.clear();
        }
      }
      if (state[s] & (kMainChanged | kAdded))
        glTextureSubImage3D(pool_texture_, 0, at.x, at.y, at.z, kSlotTexels, kSlotTexels,
                            kSlotTexels, GL_RGBA, GL_UNSIGNED_BYTE, main);
      if (smooth_texture_ && (state[s] & (kSmoothChanged | kAdded)))
        glTextureSubImage3D(smooth_texture_, 0, at.x, at.y, at.z, kSlotTexels, kSlotTexels,
                            kSlotTexels, GL_RG, GL_UNSIGNED_SHORT, smoothed);
    }
    if (!compares.empty()) reportSlotChanges(volume, compares, changes);
    st.upload_ms += msSince(t0);
  }
}

BrickPool::UpdateStats BrickPool::update(const Volume& volume, const LightVolume& light, bool fresh,
                                         const std::vector<glm::ivec3>& changed_bricks,
                                         const VoxelBox& light_box,
                                         const LightByteChanges* light_bytes,
                                         std::vector<SlotChange>* changes,
                                         const VoxelBox* density_box, ChangeDetail detail) {
  UpdateStats st;
  auto t0 = std::chrono::steady_clock::now();
  const glm::ivec3 bd = volume.brickDims();
  if (fresh || bd != brick_dims_) {
    fresh = true;
    resetTables(bd);
  }
  const std::vector<Repack> candidates = slotCandidates(volume, fresh, changed_bricks, density_box);
  VoxelBox indirection_changed;
  std::vector<Repack> to_upload;
  assignSlots(volume, fresh, candidates, &to_upload, &indirection_changed, changes, &st);
  addLightReaders(volume, light_box, light_bytes, &to_upload);
  // Added slots not given (a full pool) are not uploaded.
  std::erase_if(to_upload,
                [&](const Repack& r) { return slot_of_brick_[brickIndex(r.brick)].w == 0; });
  st.pack_ms += msSince(t0);
  uploadSlots(volume, light, !fresh && detail == ChangeDetail::kTexels, to_upload, changes, &st);
  st.slots_uploaded = int(to_upload.size()) - st.slots_unchanged;
  t0 = std::chrono::steady_clock::now();
  uploadIndirection(fresh ? VoxelBox{glm::ivec3(0), bd} : indirection_changed);
  st.upload_ms += msSince(t0);
  return st;
}

}  // namespace cb
