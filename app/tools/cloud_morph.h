// Morphing one cloud into another (seed 002 §3.3). Particles are the density-weighted centres
// of cell_voxels³ cells of each cloud; the greedy correspondence of §3.3.1 pairs them (nearest
// unpaired target per source particle, in rounds for one-to-many, the left-over targets mapped
// back to their nearest source — and the same with the roles swapped when the target has fewer
// particles); each pair moves along the quadratic B-spline through source, refining point
// (Eq. 10.1–10.3) and target (§3.3.2). A frame carries every voxel's density along its cell's
// path(s), mass-conserving trilinear splats: the source's voxels forward, the target's voxels
// backward from the target, blended (1 − t)·source' + t·target'. So t = 0 and t = 1 give the
// source and target themselves and the total density is the linear blend of the two totals
// (up to what clamping at the volume's faces moves).
//
// A frame is computed in parallel and is still the same bytes on any thread count: the splats
// are first placed (chunks of a fixed size), then sorted by the z plane of their base corner
// keeping their order (a stable counting sort), and each output plane z is written by one task
// that adds the splats based at z − 1 and then those based at z, each in that order.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "app/volume/box.h"
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
  // The same into `out` (the source's dims and world box), reusing its storage: the planes the
  // previous frame wrote (`previous`, as returned by the last call; empty for a zeroed volume)
  // are cleared, the new frame is splatted, their union is marked dirty and the box holding
  // the new frame's density is returned. For animation; calls must not overlap.
  VoxelBox frameInto(float t, Volume* out, const VoxelBox& previous) const;
  // The straightforward scatter of the first version: one thread, a fresh volume, every splat
  // added in carried-voxel order (the benchmark's baseline).
  Volume frameOneThreadReference(float t) const;
  size_t pairCount() const { return paths_.size(); }
  // Splats per in-between frame (carried voxels times their paths).
  size_t splatCount() const { return items_.size(); }

 private:
  struct Path {
    glm::vec3 source, refine, target;  // continuous voxel coordinates
    glm::vec3 at(float t) const {
      const float s = 1.0f - t;
      return s * s * source + 2.0f * s * t * refine + t * t * target;
    }
  };
  // One voxel carried along one path of its cell: at t it sits at offset + path.at(t).
  struct CarriedSplat {
    glm::vec3 offset;  // voxel centre minus the path's source (or target) end
    float mass;        // density / number of paths of its cell
    uint32_t path;
  };
  struct PlacedSplat {
    glm::vec3 p;  // continuous index, clamped to the grid (voxel centres at integers)
    float mass;
  };
  Volume blank_;
  std::vector<Path> paths_;
  std::vector<CarriedSplat> items_;  // the source's voxels first, then the target's
  size_t source_items_ = 0;
  // Scratch of frameInto (kept between frames so animation allocates nothing).
  mutable std::vector<PlacedSplat> placed_, sorted_;
  mutable std::vector<uint32_t> plane_counts_;  // per chunk, per z plane
  mutable std::vector<size_t> plane_start_;     // first sorted splat of each z plane (+ end)
};

// One-shot: plan and frame.
Volume morph(const Volume& source, const Volume& target, float t, const MorphParams& params = {});

}  // namespace cb
