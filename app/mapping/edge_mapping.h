// Edge mapping, sphere-based (thesis §6.6.2). Every non-empty footprint pixel left uncovered by
// circle growth finds its nearest circle (distance D_min to the circle's rim), is placed at the
// tangent point P_t of its view ray (the ray's closest approach to the nearest sphere's centre
// P_S), and scattered around it with a Gaussian of σ = R_S/3:
//   P_f = P_t + R_S · GaussianRand() / 3                                   (§6.6.2)
// The scatter runs along the view ray (depth) with σ = R_S/3 and across it with only
// `lateral_sigma_px` pixels, so seen from the paint view the pixel stays where it was painted.
// Voxel density is the footprint value (times density_scale), max-merged.
// Without any circle (a footprint too thin for one) a pixel is placed on the canvas mid-plane
// instead and scattered across the slab's thickness (the canvas-based mapping of §6.6.1).
#pragma once

#include <cstdint>
#include <vector>

#include "app/brush/stroke_result.h"
#include "app/mapping/circle_growth.h"
#include "app/mapping/mapping_config.h"
#include "app/mapping/paint_view_geometry.h"
#include "app/mapping/sphere_mapping.h"
#include "app/volume/volume.h"

namespace cb {

struct EdgeMappingStats {
  long long leftover_pixels = 0;    // non-empty and not covered by a circle
  long long mapped_pixels = 0;      // at least one scatter sample landed in the volume
  long long off_canvas_pixels = 0;  // no circle and the ray missed the canvas (fallback plane)
};

struct EdgeMappingInput {
  const Footprint* footprint = nullptr;
  const std::vector<uint8_t>* covered = nullptr;  // from circle growth; may be null (none)
  const std::vector<Circle>* circles = nullptr;
  const std::vector<MappedSphere>* spheres = nullptr;  // one per circle
  const PaintViewGeometry* view = nullptr;
  Canvas canvas;
  glm::vec3 fallback_point{0.0f};
  float max_distance = 1e9f;
  uint32_t stroke_index = 0;
  float empty_threshold = 0.05f;
};

// Max-merges the edge samples into the volume; returns the voxels touched (no markDirty).
VoxelBox mapEdges(const EdgeMappingInput& input, const EdgeMappingConfig& config, Volume& volume,
                  EdgeMappingStats* stats);

}  // namespace cb
