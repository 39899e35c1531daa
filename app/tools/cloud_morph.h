// Morphing one cloud into another (seed 002 §3.3). Particles are the density-weighted centres
// of cell_voxels³ cells of each cloud; the greedy correspondence of §3.3.1 pairs them (nearest
// unpaired target per source particle, in rounds for one-to-many, the left-over targets mapped
// back to their nearest source — and the same with the roles swapped when the target has fewer
// particles); each pair moves along the quadratic B-spline through source, refining point
// (Eq. 10.1–10.3) and target (§3.3.2). A frame carries every voxel's density along its cell's
// path(s), mass-conserving trilinear splats: the source's voxels forward, the target's voxels
// backward from the target, blended (1 − t)·source' + t·target'. So t = 0 and t = 1 give the
// source and target themselves and the total density is the linear blend of the two totals
// (up to what clamping at the volume's faces moves). Deterministic (seeded, one thread).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "app/volume/volume.h"

namespace cb {

struct MorphParams {
  uint32_t seed = 1;
  int cell_voxels = 8;              // particle cell edge, in voxels
  float density_threshold = 1e-4f;  // voxels at or below this carry nothing
  float refine_scale = 0.25f;       // h of Eq. (10.3) times this (1: the seed's)
};

class CloudMorph {
 public:
  // Plans the morph (ToolError kMismatchedVolumes / kEmptyVolume). The volumes are copied
  // (only their non-empty voxels).
  CloudMorph(const Volume& source, const Volume& target, const MorphParams& params = {});
  // The in-between cloud at t in [0, 1] (clamped), on the source's grid.
  Volume frame(float t) const;
  size_t pairCount() const { return paths_.size(); }

 private:
  struct Path {
    glm::vec3 source, refine, target;  // continuous voxel coordinates
    glm::vec3 at(float t) const {
      const float s = 1.0f - t;
      return s * s * source + 2.0f * s * t * refine + t * t * target;
    }
  };
  struct CarriedVoxel {
    glm::vec3 position;  // voxel centre
    float mass;          // density / number of paths of its cell
    uint32_t first_path, path_count;
  };
  Volume blank_;
  std::vector<Path> paths_;
  std::vector<uint32_t> source_path_ids_, target_path_ids_;
  std::vector<CarriedVoxel> source_voxels_, target_voxels_;
};

// One-shot: plan and frame.
Volume morph(const Volume& source, const Volume& target, float t, const MorphParams& params = {});

}  // namespace cb
