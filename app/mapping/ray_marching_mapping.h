// The initial ray-marching mapping (thesis §6.1, Fig. 6.1): every non-empty footprint pixel
// casts its paint-view ray into the canvas slab. From B, where the ray meets the canvas
// mid-plane, voxels grow outwards along the ray towards the slab's ceiling i1 and floor i2, for
// the fraction of each half given by the pixel's value (value 1 fills i1..i2). Selectable per
// stroke, mainly for comparison: seen from the side it shows the streaks of Fig. 6.2.
#pragma once

#include "app/brush/stroke_result.h"
#include "app/mapping/mapping_config.h"
#include "app/mapping/paint_view_geometry.h"
#include "app/volume/volume.h"

namespace cb {

struct RayMarchingStats {
  long long pixels = 0;           // non-empty footprint pixels
  long long mapped_pixels = 0;    // whose segment overlaps the volume
  long long parallel_pixels = 0;  // ray parallel to the canvas, or the slab behind the eye
};

// Max-merges the segments into the volume (parallel over z slabs); returns the voxels touched
// (no markDirty).
VoxelBox mapRayMarching(const Footprint& footprint, const PaintViewGeometry& view,
                        const Canvas& canvas, const RayMarchingConfig& config,
                        float empty_threshold, Volume& volume, RayMarchingStats* stats);

}  // namespace cb
