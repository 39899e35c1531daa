// The part of the sky a modelling tool works on ("a sky without walls"). Morph and wind
// were written for the one-box sky, where they walk every voxel and the wind's 64³ cells cover
// the box; in a sky of span home boxes across (app/volume/sky_extent.h) that would cost span²
// times as much and make the wind's cells span times coarser. So a tool works on a window: the
// window is cropped out as a volume of its own (its own dims and world box), the unchanged tool
// runs on it, and its result is pasted back, only the bricks that changed marked dirty (the
// renderer uploads and the history stores those alone).
//
// The window (toolWindow):
//   - a volume that is not a sky, or a one-box sky (span 1: every journal recorded before the
//     sky grew): the whole volume, so every earlier result is the same bytes;
//   - a wider sky: the full height, and along x and z the content (the bricks holding density;
//     source ∪ target for a morph) grown by a margin of an eighth of a home box (rounded up to
//     whole bricks), clipped to the sky, then
//       a. when that fits in one home-box tile (tiles are home-box sized and aligned with the
//          home box, plus one flush with each edge of the sky): that tile, so a cloud inside
//          the home box (or inside any tile) morphs and blows exactly as in the one-box sky;
//       b. else, when it is at most a home box across: a home box across, centred on it
//          (snapped to bricks, shifted into the sky);
//       c. else: itself, snapped out to bricks.
//     So a window is at least one home box across, and it is decided from the voxels alone (the
//     journalled state), so replay finds the same window.
// Along the window the wind keeps the home box's cells: 64 per home box (WindParams' 64 cells
// over the home box's width), the count scaled with the window; its updraft gust keeps the
// home box's radius and sits at the window's centre (cloud_animation.h). A cloud carried past
// the window's faces leaves it, as it leaves the one-box sky at its walls.
#pragma once

#include <glm/glm.hpp>

#include "app/volume/box.h"
#include "app/volume/volume.h"
#include "app/volume/volume_paste.h"

namespace cb {

struct ToolWindow {
  VoxelBox box;               // the window's voxels in the volume
  glm::vec3 world_min{0.0f};  // its world box (the volume's own when whole)
  glm::vec3 world_max{0.0f};
  glm::ivec3 wind_cells{64};  // the wind's velocity cells over it
  float gust_radius = 0.0f;   // world units; 0: a quarter of the window's width (whole)
  bool whole = true;          // the window is the whole volume
  glm::ivec3 dims() const { return box.hi - box.lo; }
};

// The box of the bricks holding a non-zero voxel (empty when none); only allocated bricks are
// looked into.
VoxelBox densityBricks(const Volume& volume);

// The window of `volume` for content `content` (voxels; see the header comment). An empty
// content gives the whole volume (the tools then name the empty cloud).
ToolWindow toolWindow(const Volume& volume, const VoxelBox& content);
// The window for the volume's own content (wind).
ToolWindow toolWindow(const Volume& volume);
// The window for two clouds of the same sky (a morph's source and target): their content's union.
ToolWindow toolWindow(const Volume& source, const Volume& target);

// The world box of `box` of `volume`: the volume's own for its bounds, else the box's corners.
void windowWorldBox(const Volume& volume, const VoxelBox& box, glm::vec3* world_min,
                    glm::vec3* world_max);

// The window's voxels of `volume` as a volume of their own over [world_min, world_max] (for a
// display copy at another resolution: `box` in that volume's voxels, the world box the window's).
Volume cropToWindow(const Volume& volume, const VoxelBox& box, glm::vec3 world_min,
                    glm::vec3 world_max);
Volume cropToWindow(const Volume& volume, const ToolWindow& window);

// The window's box in a volume of half the resolution (halfResolution, cloud_animation.h): the
// voxels whose 2×2×2 lie in `box` (exact when box.lo is even on every axis).
VoxelBox halfBox(const VoxelBox& box);

}  // namespace cb
