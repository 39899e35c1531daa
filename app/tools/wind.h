// Wind (seed 004 Part III "Fluid dynamics model", after Stam's stable fluids; the
// thesis §8.1 names dynamics as future work): a coarse velocity grid over the volume's world box
// that moves the density. One step (seed 004's loop without the diffusion step, ν = 0):
//   1. self-advection of the velocity, semi-Lagrangian: u(x) ← u(x − u(x)·dt)        Eq. (3.7)
//   2. projection onto ∇·u = 0 (Eq. 3.1): ∇²p = ∇·u by a fixed number of Jacobi sweeps (the
//      relaxation of Eq. 3.11/3.12 applied to the pressure Poisson equation), u ← u − ∇p
//   3. the density is carried by the same semi-Lagrangian backtrace (Eq. 3.7), but through a
//      flow map rather than step by step: the solver keeps, on its velocity grid, the
//      displacement D(x) from where each point is now back to where its air was at the start
//      (D ← D(x − u·dt) − u·dt each step, the characteristic map of Tessendorf & Pelfrey, "The
//      characteristic map for fast and efficient VFX fluid simulations", 2011), and the density
//      shown is the starting density sampled once, trilinearly, at x + D(x), times
//      exp(−dissipation·t). One resampling whatever the number of steps: the density does not
//      blur step after step, and the state after N steps costs N coarse steps plus one pass
//      over the voxels (what makes "apply" cheap).
// Forces are added between steps (Eq. 3.5: u ← u + dt·F). Boundaries are open: velocity and
// displacement samples clamp to the border cell (air coming in from outside carries the
// outside's density, 0), pressure outside the grid is 0 and density outside is 0.
// Every cell and voxel is computed independently from the previous state, so the bytes are the
// same on any thread count; zero velocity leaves the density bit for bit (the displacement
// stays +0, the sample lands on the voxel centre and the interpolation weights are exactly 0
// and 1).
#pragma once

#include <cstdint>
#include <memory>
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
  // Step 3's flow map: the displacement back to the start advected by the current velocity.
  void advectFlowMap(float dt);
  // stepVelocity then advectFlowMap.
  void step(float dt);
  // The density now: `start` (the density when the solver was still, on any grid over the
  // solver's world box) carried by the flow map, into `out` (the same dims and box). 8³ blocks
  // whose samples can only reach empty blocks of `start` are written as zeros without sampling
  // (the same bytes: the interpolation of zeros is +0). The blocks `previous` covers (what the
  // last call returned; the bounds for a volume holding anything else) and those that can hold
  // density are rewritten and marked dirty; the box of the latter is returned.
  // `every_block` samples every block (the tests' reference for the skipping).
  // What is read of `start` (a dense copy and its occupied blocks) is kept for the next call
  // with the same start (its instance and generation): an animation resamples one start every
  // frame. Not for concurrent calls on one solver.
  VoxelBox resampleDensity(const Volume& start, Volume* out, const VoxelBox& previous,
                           bool every_block = false) const;
  // The first version of step 3: the density itself advected by one step, every voxel of its
  // non-zero box grown by the largest displacement sampled. Wind records of journal
  // specification 1.1 are recomputed with it; it is the benchmark's baseline.
  VoxelBox advectDensityEveryVoxel(float dt, Volume* density);

  glm::ivec3 grid() const { return params_.grid; }
  glm::vec3 cellSize() const { return cell_; }
  glm::vec3 velocityAt(glm::ivec3 cell) const { return velocity_[index(cell.x, cell.y, cell.z)]; }
  // The flow map's displacement at a cell (world units) and the time it covers (seconds).
  glm::vec3 displacementAt(glm::ivec3 cell) const {
    return displacement_[index(cell.x, cell.y, cell.z)];
  }
  double elapsed() const { return elapsed_; }
  // Trilinear velocity at a world point (clamped to the border cells).
  glm::vec3 sampleVelocity(glm::vec3 world) const;
  // Largest |∇·u| over the cells (central differences), after a projection ≈ 0.
  float maxDivergence() const;

 private:
  size_t index(int x, int y, int z) const {
    return (size_t(z) * params_.grid.y + y) * params_.grid.x + x;
  }
  glm::vec3 sampleVelocityInCells(glm::vec3 c) const;
  // ∇·u into out; with first_sweep, also the first Jacobi sweep from p = 0 into it.
  void divergence(std::vector<float>* out, std::vector<float>* first_sweep = nullptr) const;
  void project();
  glm::ivec3 reachInVoxels(float dt, const Volume& density) const;

  WindParams params_;
  glm::vec3 world_min_, cell_;
  std::vector<glm::vec3> velocity_, scratch_velocity_;
  std::vector<glm::vec3> displacement_, scratch_displacement_;  // the flow map, world units
  double elapsed_ = 0.0;
  std::vector<float> divergence_, pressure_, scratch_pressure_;
  HugePageVector<float> scratch_density_;
  struct StartCopy;  // wind.cpp
  mutable std::shared_ptr<const StartCopy> start_copy_;
  const StartCopy& startCopy(const Volume& start) const;
};

}  // namespace cb
