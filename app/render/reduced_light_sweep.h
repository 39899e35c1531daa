// The light at reduced resolution, for feedback while the light ball is dragged (after the
// thesis's 128³ light volume for a 256³ cloud): the density is averaged over divisor³ blocks,
// the light is swept on that coarse grid with the existing sweep (sweepLightVolume), and the
// coarse transmittance over the cloud's box is handed to the renderer as bytes
// (LightPreviewGrid), which it uploads as a small 3D texture read in place of the light in the
// brick pool (volume_pool.glsl, CB_LIGHT_PREVIEW). The full light volume and the pool are not
// touched while the light moves; the release sweeps the light volume in full. The coarse step is
// `divisor` voxels long, so its extinction is 1 − (1 − k)^divisor (exact for density 1).
//
// The block averages follow the sparse volume (only coarse bricks under allocated fine bricks)
// and are kept while the volume stays the same (its instance and generation): a drag sweeps the
// same density under a moving light.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "app/render/light_volume.h"
#include "app/volume/volume.h"

namespace cb {

// The coarse light as bytes over a box of the coarse grid: coarse voxel j covers fine voxels
// [j·divisor, (j + 1)·divisor) on each axis (its centre at fine position (j + ½)·divisor).
struct LightPreviewGrid {
  int divisor = 0;             // fine voxels per coarse voxel (0: no grid)
  glm::ivec3 lo{0};            // the box's first coarse voxel
  glm::ivec3 size{0};          // coarse voxels per axis
  std::vector<uint8_t> bytes;  // unorm8 of T, x fastest (what the GPU copy holds)
  // T at fine voxel-space position p (voxel i covers [i, i + 1)), filtered as the texture unit
  // does: trilinear between coarse voxel centres, clamped to the box's edge (for tests).
  float sample(glm::vec3 p) const;
};

class ReducedLightSweep {
 public:
  // At most this many coarse voxels (bytes) in a grid: a wider cloud is swept at a coarser
  // divisor (doubled until it fits), so a preview of the whole sky stays a few megabytes.
  static constexpr size_t kMaxGridVoxels = size_t(1) << 22;

  // The light of `volume` under `light` on a grid `divisor` (≥ 2) or, for a wide cloud, a
  // multiple of it times coarser per axis, over the box of the coarse voxels the cloud's
  // allocated bricks cover grown by one (so filtering at the cloud's edge reads swept values).
  const LightPreviewGrid& sweep(const Volume& volume, const Light& light, int divisor);

 private:
  Volume coarse_{glm::ivec3(1)};
  LightVolume coarse_light_;
  LightPreviewGrid grid_;
  // What coarse_ averages: the volume's instance and generation and the divisor (0: nothing).
  uint64_t averaged_id_ = 0, averaged_generation_ = 0;
  int averaged_divisor_ = 0;
};

}  // namespace cb
