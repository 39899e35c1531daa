// Morphing one cloud into another (seed 002 §3.3). Particles are the density-weighted centres
// of cell_voxels³ cells of each cloud; the greedy correspondence of §3.3.1 pairs them (nearest
// unpaired target per source particle, in rounds for one-to-many, the left-over targets mapped
// back to their nearest source — and the same with the roles swapped when the target has fewer
// particles); each pair moves along the quadratic B-spline through source, refining point
// (Eq. 10.1–10.3) and target (§3.3.2). That is the plan (`MorphPlan`), made once from the two
// clouds at full resolution.
//
// A frame carries every voxel's density along its cell's path(s) with mass-conserving trilinear
// splats: the source's voxels forward, the target's voxels backward from the target, blended
// (1 − t)·source' + t·target'. So t = 0 and t = 1 give the source and target themselves and the
// total density is the linear blend of the two totals (up to what clamping at the volume's
// faces moves). A voxel does not move rigidly with its cell (that showed the cells as blocks):
// its displacement is the cells' mean displacements interpolated trilinearly between cell
// centres (over the non-empty cells), plus its own path's departure from its cell's mean
// weighted by a window that is 1 in the inner half of the cell and falls to 0 at its faces.
// Both parts are continuous across cell faces, so in-betweens have no seams or cracks; the
// paths are quadratic in t, so each voxel's displacement is 2st·U + t²·V (source) or
// s²·U + 2st·V (target, s = 1 − t), with U and V fixed when the voxel is carried.
//
// `CloudMorph` carries one pair of clouds along a plan: the planned clouds themselves, or the
// same clouds at a coarser grid over the same world box (the painter's half-resolution display
// copy), which then moves exactly as the full-resolution frame does.
//
// A frame is computed in parallel and is still the same bytes on any thread count: the splats
// are first placed (chunks of a fixed size), then sorted by the z plane of their base corner
// keeping their order (a stable counting sort), and each output plane z is written by one task
// that adds the splats based at z − 1 and then those based at z, each in that order. Planning
// and carrying are parallel by fixed slabs and merged in slab order.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "app/volume/box.h"
#include "app/volume/volume.h"

namespace cb {

struct MorphParams {
  uint32_t seed = 1;
  int cell_voxels = 8;              // particle cell edge, in voxels of the planned grid
  float density_threshold = 1e-4f;  // voxels at or below this carry nothing
  float refine_scale = 0.25f;       // h of Eq. (10.3) times this (1: the seed's)
};

// The correspondence and paths between two clouds (ToolError kMismatchedVolumes /
// kEmptyVolume), in continuous voxel coordinates of their grid (voxel centres at i + 0.5).
class MorphPlan {
 public:
  MorphPlan(const Volume& source, const Volume& target, const MorphParams& params = {});

  struct Path {
    glm::vec3 source, refine, target;
  };
  // Per cell of one side: its particle's index (−1: an empty cell), and per particle its paths
  // and their mean (refine − anchor, other end − anchor), anchor the side's own end.
  struct Side {
    std::vector<int> cell_particle;
    std::vector<std::vector<uint32_t>> particle_paths;
    std::vector<glm::vec3> mean_u, mean_v;
  };

  const MorphParams& params() const { return params_; }
  glm::ivec3 dims() const { return dims_; }
  glm::vec3 worldMin() const { return world_min_; }
  glm::vec3 worldMax() const { return world_max_; }
  glm::ivec3 cells() const { return cells_; }
  const std::vector<Path>& paths() const { return paths_; }
  const Side& side(bool source) const { return source ? source_ : target_; }

 private:
  MorphParams params_;
  glm::ivec3 dims_, cells_;
  glm::vec3 world_min_, world_max_;
  std::vector<Path> paths_;
  Side source_, target_;
};

class CloudMorph {
 public:
  // Plans the morph (MorphPlan) and carries the two clouds along it.
  CloudMorph(const Volume& source, const Volume& target, const MorphParams& params = {});
  // Carries `source` and `target` along `plan`: on the plan's grid, or a coarser grid over the
  // same world box (ToolError kMismatchedVolumes otherwise). Only their non-empty voxels are
  // kept.
  CloudMorph(std::shared_ptr<const MorphPlan> plan, const Volume& source, const Volume& target);

  // The in-between cloud at t in [0, 1] (clamped), on the carried clouds' grid.
  Volume frame(float t) const;
  // The same into `out` (the carried dims and world box), reusing its storage: the planes the
  // previous frame wrote (`previous`, as returned by the last call; empty for a zeroed volume)
  // are cleared, the new frame is splatted, their union is marked dirty and the box holding
  // the new frame's density is returned. For animation; calls must not overlap.
  VoxelBox frameInto(float t, Volume* out, const VoxelBox& previous) const;
  // The straightforward scatter: one thread, a fresh volume, every splat added in carried-voxel
  // order (the benchmark's baseline; equal to frame() up to float summation order).
  Volume frameOneThreadReference(float t) const;

  const std::shared_ptr<const MorphPlan>& plan() const { return plan_; }
  size_t pairCount() const { return plan_->paths().size(); }
  // Splats per in-between frame (carried voxels times their paths).
  size_t splatCount() const { return items_.size(); }

 private:
  // One voxel carried along one path: at t it sits at at0 + c1(t)·u + c2(t)·v (continuous
  // index, voxel centres at integers); c1, c2 = 2st, t² for the source, s², 2st for the target.
  struct CarriedSplat {
    glm::vec3 at0, u, v;
    float mass;  // density / number of paths of its cell
  };
  struct PlacedSplat {
    glm::vec3 p;  // continuous index, clamped to the grid (voxel centres at integers)
    float mass;
  };
  void carry(const Volume& cloud, bool source);
  glm::vec3 place(size_t item, float t) const;

  std::shared_ptr<const MorphPlan> plan_;
  Volume blank_;
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
