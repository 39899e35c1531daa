// Copying one volume's voxels into another at an offset, following the bricks: the tools' results
// pasted back into the sky (app/tools/tool_window.h), a home-box cloud placed in a sky
// (sky_extent.h).
#pragma once

#include <glm/glm.hpp>

#include "app/volume/box.h"
#include "app/volume/volume.h"

namespace cb {

// Copies `region` of `from` (a tool's result on a window, a cloud placed in a sky) into `into` at
// region.lo + at. Rows that are already equal are not written; the bricks of `into` that changed
// are marked dirty (each run of changed bricks along x its own box, or — past 64 runs, so the
// volume's kept change list never overflows — the box around them). Returns the box around the
// changed bricks, clipped to the pasted region (empty: nothing changed).
VoxelBox pasteVolume(const Volume& from, const VoxelBox& region, glm::ivec3 at, Volume* into);

}  // namespace cb
