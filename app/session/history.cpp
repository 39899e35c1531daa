#include "app/session/history.h"

#include <cstring>
#include <stdexcept>

#include <zstd.h>

namespace cb {
namespace {

// zstd level 1: the deltas are mostly zero words, which the fastest level already squeezes to a
// few percent; higher levels cost milliseconds per step for little.
constexpr int kZstdLevel = 1;

VoxelBox brickBox(glm::ivec3 brick, const Volume& volume) {
  const glm::ivec3 lo = brick * History::kBrickSize;
  return VoxelBox{lo, lo + History::kBrickSize}.intersect(volume.bounds());
}

// Calls fn(brick_box) for each brick of `box`, z-major then y then x (a fixed order).
template <typename Fn>
void forEachBrick(const VoxelBox& box, const Volume& volume, Fn&& fn) {
  if (box.empty()) return;
  const glm::ivec3 lo = box.lo / History::kBrickSize;
  const glm::ivec3 hi = (box.hi + (History::kBrickSize - 1)) / History::kBrickSize;
  for (int z = lo.z; z < hi.z; ++z)
    for (int y = lo.y; y < hi.y; ++y)
      for (int x = lo.x; x < hi.x; ++x) fn(glm::ivec3(x, y, z), brickBox({x, y, z}, volume));
}

}  // namespace

History::History(size_t limit_bytes) : limit_bytes_(limit_bytes) {}

void History::reset(const Volume& volume) {
  committed_ = volume;
  committed_generation_ = volume.generation();
  committed_instance_ = volume.instanceId();
  steps_.clear();
  cursor_ = 0;
  delta_bytes_ = 0;
}

void History::record(const Volume& volume, const SceneState& before, const SceneState& after,
                     const std::string& label) {
  if (volume.instanceId() != committed_instance_ || volume.dims() != committed_.dims()) {
    reset(volume);  // a different cloud: nothing to undo into
    return;
  }
  Step step;
  step.label = label;
  step.before = before;
  step.after = after;
  // The XOR of each changed brick, brick after brick; unchanged bricks are skipped.
  std::vector<uint32_t> words;
  const VoxelBox dirty = volume.dirtySince(committed_generation_);
  forEachBrick(dirty, volume, [&](glm::ivec3 brick, const VoxelBox& box) {
    const size_t start = words.size();
    bool changed = false;
    for (int z = box.lo.z; z < box.hi.z; ++z)
      for (int y = box.lo.y; y < box.hi.y; ++y) {
        const size_t row = volume.index(box.lo.x, y, z);
        const int n = box.hi.x - box.lo.x;
        const float* now = volume.data() + row;
        float* old = committed_.data() + row;
        for (int i = 0; i < n; ++i) {
          uint32_t a, b;
          std::memcpy(&a, now + i, 4);
          std::memcpy(&b, old + i, 4);
          words.push_back(a ^ b);
          changed |= a != b;
        }
        std::memcpy(old, now, size_t(n) * sizeof(float));  // the copy follows the cloud
      }
    if (changed)
      step.bricks.push_back(brick);
    else
      words.resize(start);
  });
  committed_generation_ = volume.generation();
  const bool scene_changed =
      std::memcmp(&before.canvas, &after.canvas, sizeof(Canvas)) != 0 ||
      before.camera.eye != after.camera.eye || before.camera.target != after.camera.target ||
      before.camera.fov_y_deg != after.camera.fov_y_deg ||
      before.light.direction != after.light.direction || before.light.colour != after.light.colour;
  if (step.bricks.empty() && !scene_changed) return;
  step.raw_bytes = words.size() * sizeof(uint32_t);
  if (!words.empty()) {
    step.compressed.resize(ZSTD_compressBound(step.raw_bytes));
    const size_t n = ZSTD_compress(step.compressed.data(), step.compressed.size(), words.data(),
                                   step.raw_bytes, kZstdLevel);
    if (ZSTD_isError(n))
      throw std::runtime_error(std::string("history: zstd: ") + ZSTD_getErrorName(n));
    step.compressed.resize(n);
    step.compressed.shrink_to_fit();
  }
  while (steps_.size() > cursor_) {  // a new step forgets what could be redone
    delta_bytes_ -= steps_.back().compressed.size();
    steps_.pop_back();
  }
  delta_bytes_ += step.compressed.size();
  steps_.push_back(std::move(step));
  ++cursor_;
  while (delta_bytes_ > limit_bytes_ && steps_.size() > 1) {
    delta_bytes_ -= steps_.front().compressed.size();
    steps_.pop_front();
    --cursor_;
  }
}

void History::applyDelta(const Step& step, Volume* volume) {
  if (step.bricks.empty()) return;
  std::vector<uint32_t> words(step.raw_bytes / sizeof(uint32_t));
  const size_t n =
      ZSTD_decompress(words.data(), step.raw_bytes, step.compressed.data(), step.compressed.size());
  if (ZSTD_isError(n) || n != step.raw_bytes)
    throw std::runtime_error("history: a step's delta does not decompress");
  size_t k = 0;
  VoxelBox changed;
  for (const glm::ivec3 brick : step.bricks) {
    const VoxelBox box = brickBox(brick, *volume);
    for (int z = box.lo.z; z < box.hi.z; ++z)
      for (int y = box.lo.y; y < box.hi.y; ++y) {
        const size_t row = volume->index(box.lo.x, y, z);
        float* now = volume->data() + row;
        for (int i = 0; i < box.hi.x - box.lo.x; ++i, ++k) {
          uint32_t a;
          std::memcpy(&a, now + i, 4);
          a ^= words[k];
          std::memcpy(now + i, &a, 4);
        }
        std::memcpy(committed_.data() + row, now, size_t(box.hi.x - box.lo.x) * sizeof(float));
      }
    changed = changed.unite(box);
  }
  volume->markDirty(changed);
  committed_generation_ = volume->generation();
}

bool History::undo(Volume* volume, SceneState* scene, std::string* label) {
  if (!canUndo() || volume->instanceId() != committed_instance_) return false;
  const Step& step = steps_[cursor_ - 1];
  // The session records every edit as a step as it ends, so the committed copy equals the
  // volume here and the XOR restores exactly the state before the step.
  applyDelta(step, volume);
  *scene = step.before;
  if (label) *label = step.label;
  --cursor_;
  return true;
}

bool History::redo(Volume* volume, SceneState* scene, std::string* label) {
  if (!canRedo() || volume->instanceId() != committed_instance_) return false;
  const Step& step = steps_[cursor_];
  applyDelta(step, volume);
  *scene = step.after;
  if (label) *label = step.label;
  ++cursor_;
  return true;
}

}  // namespace cb
