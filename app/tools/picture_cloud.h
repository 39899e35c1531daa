// Picture → cloud (seed 002 §3.1.1, §3.1.3): a shape mask is sampled with stratified particles
// (one stratum per shape pixel: the mask is the seed's traced polygon at pixel resolution),
// pulled towards the 2D medial axis (Eq. 1), stretched into depth with the linear pdf of
// Eq. (2.1)–(2.4), counted and smoothed into voxel densities (Eq. 6, 7) and max-merged into the
// volume, placed as the view sees it (tool_view.h). Deterministic: every particle's randomness is
// keyed by (seed, pixel).
#pragma once

#include <cstdint>
#include <string>

#include "app/tools/particle_density.h"
#include "app/tools/silhouette_image.h"
#include "app/tools/tool_view.h"
#include "app/volume/volume.h"

namespace cb {

struct PictureCloudParams {
  uint32_t seed = 1;
  // Particles per voxel of the stretched shape (the seed's user density D, Eq. 5).
  float particles_per_voxel = 3.0f;
  // Largest shift towards the medial axis as a fraction of Eq. (1)'s: ε is drawn in
  // [0, medial_pull]. 1 is the seed's heuristic; smaller keeps the rim (and the silhouette).
  float medial_pull = 0.3f;
  // Depth half-range = R(x, y) of Eq. (2.1) times this (1: as deep as the shape is wide).
  float depth_scale = 0.5f;
  // Particles drawn at most (the density D is lowered to fit).
  long long max_particles = 6'000'000;
  DensitySmoothing smoothing;
  // The seed's naive stretch (§3.1.1.2: z uniform in ±Z_max), the benchmark's baseline.
  bool naive_uniform_depth = false;
};

// Where the cloud of `mask` placed from `view` can write, in `volume`'s voxel grid and not clipped
// to it: the placed picture's rectangle between the nearest and farthest depth its particles are
// stretched to (Eq. 2.4), grown by the smoothing radius and a voxel. maskToCloud writes only
// inside it; the session grows the sky to hold it first (tool_view.h placementReach). ToolError
// kEmptyImage when the mask has no shape pixel.
VoxelBox pictureReach(const ShapeMask& mask, const ToolView& view, const PictureCloudParams& params,
                      const Volume& volume);

// Loads the PNG (all checks before the volume is touched; ToolError on a bad picture) and
// writes its cloud. Returns the changed box (also marked dirty on the volume).
VoxelBox pictureToCloud(const std::string& png_path, const ToolView& view,
                        const PictureCloudParams& params, Volume* volume);
// The same from a mask already in memory (kEmptyImage if it has no shape pixel).
VoxelBox maskToCloud(const ShapeMask& mask, const ToolView& view, const PictureCloudParams& params,
                     Volume* volume);

}  // namespace cb
