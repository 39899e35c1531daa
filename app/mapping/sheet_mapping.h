// The sheet stroke (thesis §7.7.5 problem 1: the study's users found stratus and
// cirrostratus layers tedious to build from thin strokes). The footprint is laid on the canvas
// mid-plane as a wide, thin, flat layer: every voxel near the plane takes the ink of the
// footprint pixel its plane point projects to (bilinear), times a Gaussian across the plane
// (σ = SheetConfig::sigma_voxels) and the mapping's pre-generated simplex noise (thesis §6.5's
// noise, here eroding the layer into wisps). Inverse mapping (voxel → pixel) leaves no holes
// however oblique the view; max-merged, parallel over z slabs in a fixed chunk order, so the
// result is the same on any thread count. Flat by design: the side-view anisotropy of the
// other mappings does not apply.
#pragma once

#include "app/brush/stroke_result.h"
#include "app/mapping/mapping_config.h"
#include "app/mapping/simplex_noise.h"
#include "app/volume/volume.h"

namespace cb {

struct SheetStats {
  long long voxels = 0;  // voxels given density
};

// Returns the voxels touched (no markDirty).
VoxelBox mapSheet(const Footprint& footprint, const Camera& camera, const Canvas& canvas,
                  const SheetConfig& config, const NoiseTexture& noise, float empty_threshold,
                  Volume& volume, SheetStats* stats);

}  // namespace cb
