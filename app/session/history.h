// Undo/redo of camera, canvas, light and cloud ("History"). A step stores the scene
// settings before and after it, and the cloud change as a delta of the bricks that changed: for
// each changed 16³ brick the XOR of its old and new voxel bits, all of a step's bricks in one
// zstd frame. XOR makes one delta serve both directions (old ^ delta = new, new ^ delta = old),
// and unchanged voxels XOR to zero, which compresses to almost nothing. The thesis kept whole
// volumes compressed with zlib (0.5 s per step, §3.3); `cloudbrush bench history` measures that
// as the baseline.
//
// The history keeps a copy of the cloud as of its last step, to know what a new step changed.
// It reads the volume's changed bricks (Volume::changedBricksSince); the copy is sparse like the
// volume, so it costs only the bricks that hold density.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "app/scene/camera.h"
#include "app/scene/canvas.h"
#include "app/scene/light.h"
#include "app/volume/volume.h"

namespace cb {

// What undo restores besides the cloud.
struct SceneState {
  Camera camera;
  Canvas canvas;
  Light light;
};

class History {
 public:
  static constexpr int kBrickSize = 16;

  // `limit_bytes`: deltas beyond it drop the oldest steps (never the newest).
  explicit History(size_t limit_bytes = size_t(256) << 20);

  // Starts over from `volume` as it is now (no steps).
  void reset(const Volume& volume);
  // Records a step: the scene before and after, and the cloud change since the last step (or
  // reset). A step that changes nothing is not recorded. Drops every redoable step.
  void record(const Volume& volume, const SceneState& before, const SceneState& after,
              const std::string& label);

  // The sky grew around the cloud (sky_extent.h growSky): `grown` is the volume the history's
  // volume became, each brick b now brick b + brick_offset. The committed copy and every step's
  // bricks follow, so undo and redo go on across the growth (the sky stays grown). Call it
  // between steps, when every change of the volume before the growth is recorded.
  void followGrowth(const Volume& grown, glm::ivec3 brick_offset);

  bool canUndo() const { return cursor_ > 0; }
  bool canRedo() const { return cursor_ < steps_.size(); }
  // Reverts / re-applies one step: the changed bricks are written into `volume` (marked dirty,
  // so the light volume and the renderer follow) and `scene` receives the settings to restore.
  // False (nothing done) when there is no such step; `label` names the step.
  bool undo(Volume* volume, SceneState* scene, std::string* label = nullptr);
  bool redo(Volume* volume, SceneState* scene, std::string* label = nullptr);

  size_t steps() const { return steps_.size(); }
  size_t undoable() const { return cursor_; }
  // Bytes of compressed deltas held, and the committed copy of the cloud.
  size_t deltaBytes() const { return delta_bytes_; }
  size_t copyBytes() const { return committed_.memoryBytes(); }

 private:
  struct Step {
    std::string label;
    SceneState before, after;
    std::vector<glm::ivec3> bricks;   // brick coordinates (voxel origin / kBrickSize)
    std::vector<uint8_t> compressed;  // zstd frame of the bricks' XOR words, brick after brick
    size_t raw_bytes = 0;
  };
  void applyDelta(const Step& step, Volume* volume);

  size_t limit_bytes_;
  Volume committed_{glm::ivec3(1)};
  uint64_t committed_generation_ = 0;
  uint64_t committed_instance_ = 0;
  std::deque<Step> steps_;
  size_t cursor_ = 0;  // steps_[0, cursor_) are done; the rest can be redone
  size_t delta_bytes_ = 0;
};

}  // namespace cb
