#include "app/volume/volume.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

#include "app/volume/brick_table_shift.h"

namespace cb {
namespace {
constexpr size_t kMaxKeptChanges = 256;
// toDense() refuses grids larger than a volume file may hold (volume_file_header.h).
constexpr size_t kMaxDenseVoxels = size_t(1) << 30;
std::atomic<uint64_t> g_next_instance_id{1};
uint64_t nextInstanceId() {
  return g_next_instance_id.fetch_add(1);
}

// Calls fn(brick) for each brick meeting `box`, z-major then y then x.
template <typename Fn>
void forEachBrickOf(const VoxelBox& box, Fn&& fn) {
  if (box.empty()) return;
  const glm::ivec3 lo = box.lo >> Volume::kBrickShift;
  const glm::ivec3 hi = ((box.hi - 1) >> Volume::kBrickShift) + 1;
  for (int z = lo.z; z < hi.z; ++z)
    for (int y = lo.y; y < hi.y; ++y)
      for (int x = lo.x; x < hi.x; ++x) fn(glm::ivec3(x, y, z));
}

bool allZeroBits(const float* v, int n) {
  for (int i = 0; i < n; ++i)
    if (std::bit_cast<uint32_t>(v[i]) != 0) return false;
  return true;
}
}  // namespace

Volume::Volume(glm::ivec3 dims, glm::vec3 world_min, glm::vec3 world_max)
    : dims_(dims), world_min_(world_min), world_max_(world_max), instance_id_(nextInstanceId()) {
  if (dims.x <= 0 || dims.y <= 0 || dims.z <= 0 || dims.x > kMaxVolumeDim ||
      dims.y > kMaxVolumeDim || dims.z > kMaxVolumeDim)
    throw std::invalid_argument("volume dimensions " + std::to_string(dims.x) + "x" +
                                std::to_string(dims.y) + "x" + std::to_string(dims.z) +
                                " out of range 1.." + std::to_string(kMaxVolumeDim));
  brick_dims_ = (dims + (kBrickSize - 1)) >> kBrickShift;
  const size_t bricks = size_t(brick_dims_.x) * size_t(brick_dims_.y) * size_t(brick_dims_.z);
  table_.assign(bricks, nullptr);
  brick_changed_.assign(bricks, 0);
  markDirty(bounds());
}

Volume::~Volume() {
  freeAll();
}

void Volume::freeAll() {
  for (float*& b : table_) {
    delete[] b;
    b = nullptr;
  }
  allocated_ = 0;
}

void Volume::copyBricksFrom(const Volume& o) {
  table_.assign(o.table_.size(), nullptr);
  for (size_t i = 0; i < o.table_.size(); ++i)
    if (o.table_[i]) {
      table_[i] = new float[kBrickVoxels];
      std::memcpy(table_[i], o.table_[i], kBrickBytes);
    }
  allocated_ = o.allocated_;
}

Volume::Volume(const Volume& o)
    : dims_(o.dims_),
      world_min_(o.world_min_),
      world_max_(o.world_max_),
      brick_dims_(o.brick_dims_),
      brick_changed_(o.brick_changed_),
      generation_(o.generation_),
      instance_id_(nextInstanceId()),
      changes_(o.changes_),
      growth_(o.growth_) {
  copyBricksFrom(o);
}

Volume::Volume(Volume&& o) noexcept
    : dims_(o.dims_),
      world_min_(o.world_min_),
      world_max_(o.world_max_),
      brick_dims_(o.brick_dims_),
      table_(std::move(o.table_)),
      brick_changed_(std::move(o.brick_changed_)),
      allocated_(o.allocated_),
      generation_(o.generation_),
      instance_id_(nextInstanceId()),
      changes_(std::move(o.changes_)),
      growth_(o.growth_) {
  o.table_.clear();
  o.allocated_ = 0;
}

Volume& Volume::operator=(const Volume& o) {
  if (this != &o) *this = Volume(o);
  return *this;
}

Volume& Volume::operator=(Volume&& o) noexcept {
  if (this == &o) return *this;
  freeAll();
  dims_ = o.dims_;
  world_min_ = o.world_min_;
  world_max_ = o.world_max_;
  brick_dims_ = o.brick_dims_;
  table_ = std::move(o.table_);
  brick_changed_ = std::move(o.brick_changed_);
  allocated_ = o.allocated_;
  generation_ = o.generation_;
  changes_ = std::move(o.changes_);
  growth_ = o.growth_;
  instance_id_ = nextInstanceId();
  o.table_.clear();
  o.allocated_ = 0;
  return *this;
}

float* Volume::allocateBrick(size_t i) {
  std::lock_guard<std::mutex> lock(*allocation_);
  std::atomic_ref<float*> slot(table_[i]);
  if (float* b = slot.load(std::memory_order_acquire)) return b;  // another thread was first
  float* b = new float[kBrickVoxels]();
  ++allocated_;
  slot.store(b, std::memory_order_release);
  return b;
}

bool Volume::releaseEmptyBrick(glm::ivec3 b) {
  float*& slot = table_[brickIndexOf(b)];
  if (!slot || !allZeroBits(slot, kBrickVoxels)) return false;
  delete[] slot;
  slot = nullptr;
  --allocated_;
  return true;
}

void Volume::readLine(glm::ivec3 start, int axis, int n, float* out) const {
  const size_t stride = size_t(1) << (kBrickShift * axis);
  glm::ivec3 p = start;
  for (int i = 0; i < n;) {
    const int m = std::min(kBrickSize - (p[axis] & (kBrickSize - 1)), n - i);
    const float* b = brickPointer(brickIndex(p.x, p.y, p.z));
    if (!b) {
      std::fill(out + i, out + i + m, 0.0f);
    } else if (axis == 0) {
      std::memcpy(out + i, b + voxelInBrick(p.x, p.y, p.z), size_t(m) * sizeof(float));
    } else {
      const float* s = b + voxelInBrick(p.x, p.y, p.z);
      for (int k = 0; k < m; ++k) out[i + k] = s[size_t(k) * stride];
    }
    i += m;
    p[axis] += m;
  }
}

void Volume::writeLine(glm::ivec3 start, int axis, int n, const float* in) {
  const size_t stride = size_t(1) << (kBrickShift * axis);
  glm::ivec3 p = start;
  for (int i = 0; i < n;) {
    const int m = std::min(kBrickSize - (p[axis] & (kBrickSize - 1)), n - i);
    const size_t bi = brickIndex(p.x, p.y, p.z);
    if (brickPointer(bi) || !allZeroBits(in + i, m)) {
      float* d = brickForWrite(bi) + voxelInBrick(p.x, p.y, p.z);
      for (int k = 0; k < m; ++k) d[size_t(k) * stride] = in[i + k];
    }
    i += m;
    p[axis] += m;
  }
}

bool Volume::hasDensity() const {
  for (const float* b : table_)
    if (b && std::any_of(b, b + kBrickVoxels, [](float d) { return d > 0.0f; })) return true;
  return false;
}

std::vector<float> Volume::toDense() const {
  if (voxelCount() > kMaxDenseVoxels)
    throw std::length_error("volume " + std::to_string(dims_.x) + "x" + std::to_string(dims_.y) +
                            "x" + std::to_string(dims_.z) + " too large for a dense copy (" +
                            std::to_string(kMaxDenseVoxels) + " voxels at most)");
  std::vector<float> dense(voxelCount(), 0.0f);
  for (const glm::ivec3 b : allocatedBrickList()) {
    const VoxelBox box = brickBox(b);
    const float* src = brick(b);
    for (int z = box.lo.z; z < box.hi.z; ++z)
      for (int y = box.lo.y; y < box.hi.y; ++y)
        std::memcpy(dense.data() + index(box.lo.x, y, z), src + voxelInBrick(box.lo.x, y, z),
                    size_t(box.hi.x - box.lo.x) * sizeof(float));
  }
  return dense;
}

void Volume::assignDense(const float* dense) {
  freeAll();
  forEachBrickOf(bounds(), [&](glm::ivec3 b) {
    const VoxelBox box = brickBox(b);
    const int n = box.hi.x - box.lo.x;
    for (int z = box.lo.z; z < box.hi.z; ++z)
      for (int y = box.lo.y; y < box.hi.y; ++y)
        writeLine({box.lo.x, y, z}, 0, n, dense + index(box.lo.x, y, z));
  });
  markDirty(bounds());
}

void Volume::fill(float v) {
  if (isZeroBits(v)) {
    freeAll();
  } else {
    forEachBrickOf(bounds(), [&](glm::ivec3 b) {
      const VoxelBox box = brickBox(b);
      float* d = brickForWrite(b);
      for (int z = box.lo.z; z < box.hi.z; ++z)
        for (int y = box.lo.y; y < box.hi.y; ++y)
          std::fill_n(d + voxelInBrick(box.lo.x, y, z), box.hi.x - box.lo.x, v);
    });
  }
  markDirty(bounds());
}

std::vector<glm::ivec3> Volume::allocatedBrickList() const {
  std::vector<glm::ivec3> list;
  list.reserve(allocated_);
  for (int z = 0; z < brick_dims_.z; ++z)
    for (int y = 0; y < brick_dims_.y; ++y)
      for (int x = 0; x < brick_dims_.x; ++x)
        if (table_[brickIndexOf({x, y, z})]) list.push_back({x, y, z});
  return list;
}

size_t Volume::memoryBytes() const {
  return allocated_ * kBrickBytes + table_.size() * (sizeof(float*) + sizeof(uint64_t));
}

Volume Volume::movedInto(glm::ivec3 dims, glm::vec3 world_min, glm::vec3 world_max,
                         glm::ivec3 brick_offset) && {
  Volume to(dims, world_min, world_max);
  const glm::ivec3 end = brick_offset + brick_dims_;
  if (dims_ % kBrickSize != glm::ivec3(0) || glm::any(glm::lessThan(brick_offset, glm::ivec3(0))) ||
      glm::any(glm::greaterThan(end * kBrickSize, dims)))
    throw std::invalid_argument(
        "Volume::movedInto: a " + std::to_string(dims_.x) + "x" + std::to_string(dims_.y) + "x" +
        std::to_string(dims_.z) + " grid does not go whole bricks into " + std::to_string(dims.x) +
        "x" + std::to_string(dims.y) + "x" + std::to_string(dims.z) + " at brick offset " +
        std::to_string(brick_offset.x) + "," + std::to_string(brick_offset.y) + "," +
        std::to_string(brick_offset.z));
  to.table_ = shiftedBrickTable(table_, brick_dims_, to.brick_dims_, brick_offset);
  std::fill(table_.begin(), table_.end(), nullptr);  // the bricks are `to`'s now
  to.allocated_ = allocated_;
  allocated_ = 0;
  to.markDirty(to.bounds());
  to.growth_ = {instance_id_, generation_, dims_, brick_offset, to.generation_};
  return to;
}

uint64_t Volume::markDirty(const VoxelBox& box) {
  VoxelBox clipped = box.intersect(bounds());
  if (clipped.empty()) return generation_;
  ++generation_;
  changes_.push_back({generation_, clipped});
  if (changes_.size() > kMaxKeptChanges) changes_.pop_front();
  forEachBrickOf(clipped, [&](glm::ivec3 b) { brick_changed_[brickIndexOf(b)] = generation_; });
  return generation_;
}

VoxelBox Volume::dirtySince(uint64_t since) const {
  if (since >= generation_) return {};
  if (changes_.empty() || changes_.front().generation > since + 1) return bounds();
  VoxelBox u;
  for (auto it = changes_.rbegin(); it != changes_.rend() && it->generation > since; ++it)
    u = u.unite(it->box);
  return u;
}

std::vector<glm::ivec3> Volume::changedBricksSince(uint64_t since) const {
  std::vector<glm::ivec3> list;
  forEachBrickOf(dirtySince(since), [&](glm::ivec3 b) {
    if (brick_changed_[brickIndexOf(b)] > since) list.push_back(b);
  });
  return list;
}

}  // namespace cb
