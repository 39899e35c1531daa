// Where a finished stroke's mapping can write, in world x/z, known before it is mapped: the sky
// grows to hold it first (app/volume/sky_extent.h), so the stroke lands whole instead of being
// clipped at the sky's old edge. A pure function of the stroke and the mapping configuration
// (both journalled), so a replay grows the sky at the same stroke.
//
// Every method places ink on the rays of the footprint's inked pixels: HMM spheres centred where
// circle centres' rays meet the canvas mid-plane (§6.5) with radius r_px × pixel size at that
// depth, edge pixels on their ray at a sphere's depth scattered σ ≤ R_S/3 along it (§6.6.2), ray
// marching inside the canvas slab (§6.1), sheets on the canvas. So the reach is the slice of the
// inked pixels' bounding frustum between the nearest and farthest depth where its corner rays
// cross the canvas slab, widened by twice the largest sphere radius (a sphere's extent plus six
// σ of edge scatter) and 8 voxels. It over-estimates: the sky grows by whole home boxes anyway.
#pragma once

#include <glm/glm.hpp>

#include "app/brush/stroke_result.h"
#include "app/mapping/mapping_config.h"
#include "app/volume/sky_extent.h"

namespace cb {

// `inked`: some footprint pixel is above the empty threshold; `bounded`: every corner ray crosses
// the canvas mid-plane ahead of the eye. `voxel_size`: the sky's voxel edge in world units (the
// margin's 8 voxels).
SkyReach strokeReach(const StrokeResult& stroke, const MappingConfig& config, float voxel_size);

}  // namespace cb
