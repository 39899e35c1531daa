// Which pixels a volume change can alter: the screen rectangle that a partial re-render
// (RenderOptions::region) must cover after a sync, so a pen-up re-renders the new cloud and its
// shadow instead of the whole frame.
//
// A pixel's ray reads a voxel only if the ray passes within the trilinear reach of that voxel
// (one voxel), or, for the iso-surface styles, within the central-difference offset of the
// normal; every other pixel computes exactly what it computed before the change (the ray-bounds
// skipping keeps sample positions, and newly occupied cells hold only zeros off the changed
// voxels). So the boxes of the pool texels a sync changed (BrickPool::SlotChange, per slot: the
// stroke's density and the 8-bit transmittance of its shadow, light_volume.h; for the composited
// styles only where a sample has density for the light to weigh) — grown by that reach and
// projected through the camera bound every changed pixel: their 8 corners each, the rectangle
// around them rounded outwards. A box that reaches behind the near plane (or holds the eye)
// gives the whole frame. Screen-space styles dilate the rectangle further inside render().
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "app/render/render_style.h"
#include "app/render/volume_renderer.h"
#include "app/scene/camera.h"
#include "app/volume/box.h"
#include "app/volume/volume.h"

namespace cb {

struct ScreenRegion {
  // x, y, width, height in pixels, origin at the bottom left (glScissor, RenderOptions::region).
  glm::ivec4 rect{0};
  bool whole_frame = false;  // every pixel may have changed (rect is then the whole frame)

  bool empty() const { return !whole_frame && (rect.z <= 0 || rect.w <= 0); }
  long long pixels() const { return empty() ? 0 : (long long)rect.z * rect.w; }
  // The smallest region holding both.
  ScreenRegion unite(const ScreenRegion& o) const;
  // What to pass as RenderOptions::region (zero: the whole frame; never call with empty()).
  glm::ivec4 renderRegion() const { return whole_frame ? glm::ivec4(0) : rect; }
  static ScreenRegion wholeFrame(int width, int height) {
    return {glm::ivec4(0, 0, width, height), true};
  }
};

// How far (voxels) outside a changed voxel a ray can still read it in `style`: the trilinear
// footprint, plus the normal's central-difference offset for the iso-surface styles.
float readReachVoxels(RenderStyle style, glm::vec3 voxel_size);

// The voxels of a pool slot's change (BrickPool::SlotChange) whose change can alter an image in
// `style`: `weighted` for the composited styles (a sample's light weighs nothing where its
// density is 0), `bytes` for the iso-surface styles (they read the light off the march, near a
// surface, not at a sample of known density). Empty if none.
VoxelBox visibleChange(const BrickPool::SlotChange& change, RenderStyle style);
// The non-empty ones of `changes`.
std::vector<VoxelBox> visibleChanges(const std::vector<BrickPool::SlotChange>& changes,
                                     RenderStyle style);

// The pixels of a width×height image through `camera` whose rays pass within `reach_voxels` of
// any box in `boxes` (voxel boxes of `volume`); empty when all boxes are.
ScreenRegion projectVoxelBoxes(const Camera& camera, int width, int height, const Volume& volume,
                               const std::vector<VoxelBox>& boxes, float reach_voxels);

// The pixels a sync changed in `style`: those whose rays pass near the texels it changed
// (visibleChanges of sync.changes: density and 8-bit transmittance as the pool holds them, so
// erased density counts where none is left, and a shadow's change only where 8 bits see it).
// After the light moved (SyncStats::light_moved): the whole frame.
ScreenRegion changedScreenRegion(const Camera& camera, int width, int height, const Volume& volume,
                                 const SyncStats& sync, RenderStyle style);

}  // namespace cb
