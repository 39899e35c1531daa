#include "app/volume/volume.h"

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <string>

namespace cb {
namespace {
constexpr size_t kMaxKeptChanges = 256;
std::atomic<uint64_t> g_next_instance_id{1};
uint64_t nextInstanceId() {
  return g_next_instance_id.fetch_add(1);
}
}  // namespace

Volume::Volume(glm::ivec3 dims, glm::vec3 world_min, glm::vec3 world_max)
    : dims_(dims), world_min_(world_min), world_max_(world_max), instance_id_(nextInstanceId()) {
  if (dims.x <= 0 || dims.y <= 0 || dims.z <= 0 || dims.x > kMaxVolumeDim ||
      dims.y > kMaxVolumeDim || dims.z > kMaxVolumeDim)
    throw std::invalid_argument("volume dimensions " + std::to_string(dims.x) + "x" +
                                std::to_string(dims.y) + "x" + std::to_string(dims.z) +
                                " out of range 1.." + std::to_string(kMaxVolumeDim));
  data_.assign(size_t(dims.x) * dims.y * dims.z, 0.0f);
  markDirty(bounds());
}

Volume::Volume(const Volume& o)
    : dims_(o.dims_),
      world_min_(o.world_min_),
      world_max_(o.world_max_),
      data_(o.data_),
      generation_(o.generation_),
      instance_id_(nextInstanceId()),
      changes_(o.changes_) {}

Volume::Volume(Volume&& o) noexcept
    : dims_(o.dims_),
      world_min_(o.world_min_),
      world_max_(o.world_max_),
      data_(std::move(o.data_)),
      generation_(o.generation_),
      instance_id_(nextInstanceId()),
      changes_(std::move(o.changes_)) {}

Volume& Volume::operator=(const Volume& o) {
  if (this != &o) *this = Volume(o);
  return *this;
}

Volume& Volume::operator=(Volume&& o) noexcept {
  dims_ = o.dims_;
  world_min_ = o.world_min_;
  world_max_ = o.world_max_;
  data_ = std::move(o.data_);
  generation_ = o.generation_;
  changes_ = std::move(o.changes_);
  instance_id_ = nextInstanceId();
  return *this;
}

void Volume::fill(float v) {
  std::fill(data_.begin(), data_.end(), v);
  markDirty(bounds());
}

uint64_t Volume::markDirty(const VoxelBox& box) {
  VoxelBox clipped = box.intersect(bounds());
  if (clipped.empty()) return generation_;
  ++generation_;
  changes_.push_back({generation_, clipped});
  if (changes_.size() > kMaxKeptChanges) changes_.pop_front();
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

}  // namespace cb
