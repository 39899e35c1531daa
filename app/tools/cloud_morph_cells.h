// The first morph (journal specification 1.1, `morph=` records), kept to replay those records
// exactly: each 8³ cell's voxels move rigidly along their cell's path(s), which showed the cells
// as blocks and is no longer the painter's morph (that is CloudMorph, cloud_morph.h, journalled
// as `morph2=`). Use it only when replaying a `morph=` record.
//
// The correspondence and the paths are MorphPlan's (seed 002 §3.3.1–3.3.2; the same particles,
// greedy pairs and refining points the first version made). A frame places every voxel of the
// source at offset + path(t) (offset: the voxel centre minus its path's source end), and every
// voxel of the target at offset + path(t) from its path's target end, each split evenly over
// its cell's paths, weighted 1 − t and t, as mass-conserving trilinear splats clamped to the
// grid. The splats are added in the order the 1.1 version added them (by the z plane of their
// base corner, in carried-voxel order; each plane first the splats based one plane below), so
// the bytes are that version's.
#pragma once

#include "app/tools/cloud_morph.h"
#include "app/volume/volume.h"

namespace cb {

// The cell-block morph of `source` into `target` at t in [0, 1] (clamped), on the source's
// grid (ToolError kMismatchedVolumes / kEmptyVolume as MorphPlan).
Volume morphCellBlocks(const Volume& source, const Volume& target, float t,
                       const MorphParams& params = {});

}  // namespace cb
