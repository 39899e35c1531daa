#include "app/session/history.h"

#include <bit>
#include <cstring>
#include <stdexcept>

#include <zstd.h>

namespace cb {
namespace {

// zstd level 1: the deltas are mostly zero words, which the fastest level already squeezes to a
// few percent; higher levels cost milliseconds per step for little.
constexpr int kZstdLevel = 1;

static_assert(History::kBrickSize == Volume::kBrickSize,
              "the history's deltas are the volume's bricks");

// Position of voxel p of brick storage (16³, x fastest).
size_t inBrick(glm::ivec3 p) {
  constexpr int m = Volume::kBrickSize - 1;
  return (size_t(p.z & m) * Volume::kBrickSize + size_t(p.y & m)) * Volume::kBrickSize +
         size_t(p.x & m);
}

// Makes `to`'s brick b hold what `from`'s holds (unallocated stays unallocated).
void copyBrick(const Volume& from, Volume& to, glm::ivec3 b) {
  if (const float* src = from.brick(b)) {
    std::memcpy(to.brickForWrite(b), src, Volume::kBrickBytes);
  } else if (float* dst = to.brick(b) ? to.brickForWrite(b) : nullptr) {
    std::memset(dst, 0, Volume::kBrickBytes);
    to.releaseEmptyBrick(b);
  }
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
  // The XOR of each changed brick, brick after brick (in the volume's fixed brick order), over
  // the brick's voxels inside the volume, z then y then x; unchanged bricks are skipped.
  std::vector<uint32_t> words;
  for (const glm::ivec3 brick : volume.changedBricksSince(committed_generation_)) {
    const float* now = volume.brick(brick);
    const float* old = committed_.brick(brick);
    if (!now && !old) continue;  // zero before and after
    const VoxelBox box = volume.brickBox(brick);
    const size_t start = words.size();
    bool changed = false;
    for (int z = box.lo.z; z < box.hi.z; ++z)
      for (int y = box.lo.y; y < box.hi.y; ++y)
        for (int x = box.lo.x; x < box.hi.x; ++x) {
          const size_t i = inBrick({x, y, z});
          const uint32_t a = now ? std::bit_cast<uint32_t>(now[i]) : 0u;
          const uint32_t b = old ? std::bit_cast<uint32_t>(old[i]) : 0u;
          words.push_back(a ^ b);
          changed |= a != b;
        }
    if (changed) {
      step.bricks.push_back(brick);
      copyBrick(volume, committed_, brick);  // the copy follows the cloud
    } else {
      words.resize(start);
    }
  }
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

void History::followGrowth(const Volume& grown, glm::ivec3 brick_offset) {
  for (Step& step : steps_)
    for (glm::ivec3& brick : step.bricks) brick += brick_offset;
  committed_ = std::move(committed_)
                   .movedInto(grown.dims(), grown.worldMin(), grown.worldMax(), brick_offset);
  committed_generation_ = grown.generation();
  committed_instance_ = grown.instanceId();
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
    const VoxelBox box = volume->brickBox(brick);
    float* now = volume->brickForWrite(brick);
    for (int z = box.lo.z; z < box.hi.z; ++z)
      for (int y = box.lo.y; y < box.hi.y; ++y)
        for (int x = box.lo.x; x < box.hi.x; ++x, ++k) {
          float& v = now[inBrick({x, y, z})];
          v = std::bit_cast<float>(std::bit_cast<uint32_t>(v) ^ words[k]);
        }
    volume->releaseEmptyBrick(brick);  // undoing a stroke gives its memory back
    copyBrick(*volume, committed_, brick);
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
