// The light volume at reduced resolution, for feedback while the light ball is dragged
// (after the thesis's 128³ light volume for a 256³ cloud): the density is averaged over
// divisor³ blocks, the light is swept on that coarse grid with the existing sweep
// (sweepLightVolume) and the transmittance is interpolated back to the voxels of the light bricks
// (lightBrickList, the ones the renderer reads). Both follow the sparse volume: only the coarse
// bricks under allocated fine bricks are averaged. The coarse step is `divisor` voxels long, so
// its extinction is 1 − (1 − k)^divisor (exact for density 1).
//
// The result is marked as not matching any light (extinction −1), so the next
// sweepLightVolume — at release — recomputes the whole light volume at full resolution.
#pragma once

#include "app/render/light_volume.h"
#include "app/volume/volume.h"

namespace cb {

class ReducedLightSweep {
 public:
  // Recomputes all of `light_volume` from a grid `divisor` times coarser per axis (divisor ≥ 2;
  // 1 is a plain full sweep). Returns the whole volume's box (every light brick was rewritten).
  VoxelBox sweep(LightVolume& light_volume, const Volume& volume, const Light& light, int divisor);

 private:
  Volume coarse_{glm::ivec3(1)};
  LightVolume coarse_light_;
};

}  // namespace cb
