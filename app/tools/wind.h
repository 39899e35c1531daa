// Wind (issue 14; seed 004 Part III "Fluid dynamics model", after Stam's stable fluids; the
// thesis §8.1 names dynamics as future work): a coarse velocity grid over the volume's world box
// that moves the density. One step (seed 004's loop without the diffusion step, ν = 0):
//   1. self-advection of the velocity, semi-Lagrangian: u(x) ← u(x − u(x)·dt)        Eq. (3.7)
//   2. projection onto ∇·u = 0 (Eq. 3.1): ∇²p = ∇·u by a fixed number of Jacobi sweeps (the
//      relaxation of Eq. 3.11/3.12 applied to the pressure Poisson equation), u ← u − ∇p
//   3. density advection, semi-Lagrangian at every density voxel with the trilinearly
//      interpolated coarse velocity: ρ(x) ← ρ(x − u(x)·dt) · exp(−dissipation·dt)   Eq. (3.7)
// Forces are added between steps (Eq. 3.5: u ← u + dt·F). Boundaries are open: velocity
// samples clamp to the border cell, pressure outside the grid is 0 and density outside is 0.
// Every cell and voxel is computed independently from the previous state, so the bytes are the
// same on any thread count; zero velocity leaves the density bit for bit (the backtrace lands on
// the voxel centre and the interpolation weights are exactly 0 and 1).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "app/tools/huge_page_allocator.h"
#include "app/volume/box.h"
#include "app/volume/volume.h"

namespace cb {

struct WindParams {
  glm::ivec3 grid = glm::ivec3(64);  // velocity cells over the volume's world box
  int pressure_iterations = 20;      // Jacobi sweeps per projection
  float dissipation = 0.0f;          // density fades as exp(−dissipation·t), t in seconds
};

class WindSolver {
 public:
  // The velocity grid covers [world_min, world_max] (a volume's world box), initially still.
  WindSolver(glm::vec3 world_min, glm::vec3 world_max, const WindParams& params = {});

  // Every cell's velocity set to `velocity` (world units per second).
  void setUniformWind(glm::vec3 velocity);
  // Eq. (3.5) with a force that falls off linearly from `centre` to 0 at `radius` (world units).
  void addForce(glm::vec3 force, glm::vec3 centre, float radius, float dt);
  // Steps 1 and 2: moves and projects the velocity by dt seconds.
  void stepVelocity(float dt);
  // Step 3: moves the density by the current velocity for dt seconds. Only the box that can
  // change (the density's non-zero box grown by the largest displacement) is rewritten and
  // marked dirty; it is returned. Inside it, 8³ blocks whose backtraces can only reach empty
  // blocks are written as zeros without sampling (the same bytes: the interpolation of zeros
  // is +0); which blocks hold density is kept from the previous step when `density` is the
  // volume that step wrote (same instance and generation), else found by one pass.
  VoxelBox advectDensity(float dt, Volume* density);
  // The first version of step 3: every voxel of the box sampled (the benchmark's baseline and
  // the tests' reference; the same bytes as advectDensity).
  VoxelBox advectDensityEveryVoxel(float dt, Volume* density);
  // stepVelocity then advectDensity.
  VoxelBox step(float dt, Volume* density);

  glm::ivec3 grid() const { return params_.grid; }
  glm::vec3 cellSize() const { return cell_; }
  glm::vec3 velocityAt(glm::ivec3 cell) const { return velocity_[index(cell.x, cell.y, cell.z)]; }
  // Trilinear velocity at a world point (clamped to the border cells).
  glm::vec3 sampleVelocity(glm::vec3 world) const;
  // Largest |∇·u| over the cells (central differences), after a projection ≈ 0.
  float maxDivergence() const;

 private:
  size_t index(int x, int y, int z) const {
    return (size_t(z) * params_.grid.y + y) * params_.grid.x + x;
  }
  glm::vec3 sampleVelocityInCells(glm::vec3 c) const;
  void divergence(std::vector<float>* out) const;
  void project();
  glm::ivec3 reachInVoxels(float dt, const Volume& density) const;

  WindParams params_;
  glm::vec3 world_min_, cell_;
  std::vector<glm::vec3> velocity_, scratch_velocity_;
  std::vector<float> divergence_, pressure_, scratch_pressure_;
  HugePageVector<float> scratch_density_;
  // Which 8³ blocks of the last density written hold a non-zero voxel.
  static constexpr int kBlock = 8;
  std::vector<uint8_t> block_occupied_;
  uint64_t occupancy_instance_ = 0, occupancy_generation_ = 0;
};

}  // namespace cb
