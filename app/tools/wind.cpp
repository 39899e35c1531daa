#include "app/tools/wind.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "app/core/parallel_for.h"

namespace cb {
namespace {

// a + (b − a)·t: exactly a at t = 0, so a zero displacement reproduces the input bit for bit.
template <typename T>
T lerp(T a, T b, float t) {
  return a + (b - a) * t;
}

// Trilinear sample of a grid at continuous index c (cell centres at integers), clamped to the
// border cells.
template <typename T>
T sampleClamped(const std::vector<T>& grid, glm::ivec3 n, glm::vec3 c) {
  c = glm::clamp(c, glm::vec3(0), glm::vec3(n - 1));
  const glm::ivec3 i0 = glm::min(glm::ivec3(glm::floor(c)), glm::max(n - 2, glm::ivec3(0)));
  const glm::vec3 f = c - glm::vec3(i0);
  const glm::ivec3 i1 = glm::min(i0 + 1, n - 1);
  auto at = [&](int x, int y, int z) { return grid[(size_t(z) * n.y + y) * n.x + x]; };
  const T c00 = lerp(at(i0.x, i0.y, i0.z), at(i1.x, i0.y, i0.z), f.x);
  const T c10 = lerp(at(i0.x, i1.y, i0.z), at(i1.x, i1.y, i0.z), f.x);
  const T c01 = lerp(at(i0.x, i0.y, i1.z), at(i1.x, i0.y, i1.z), f.x);
  const T c11 = lerp(at(i0.x, i1.y, i1.z), at(i1.x, i1.y, i1.z), f.x);
  return lerp(lerp(c00, c10, f.y), lerp(c01, c11, f.y), f.z);
}

// Trilinear density at continuous voxel index v (voxel centres at integers); 0 outside.
float sampleDensity(const Volume& volume, glm::vec3 v) {
  const glm::ivec3 d = volume.dims();
  const glm::ivec3 i0 = glm::ivec3(glm::floor(v));
  const glm::vec3 f = v - glm::vec3(i0);
  auto at = [&](int x, int y, int z) {
    if (x < 0 || y < 0 || z < 0 || x >= d.x || y >= d.y || z >= d.z) return 0.0f;
    return volume.data()[volume.index(x, y, z)];
  };
  const float c00 = lerp(at(i0.x, i0.y, i0.z), at(i0.x + 1, i0.y, i0.z), f.x);
  const float c10 = lerp(at(i0.x, i0.y + 1, i0.z), at(i0.x + 1, i0.y + 1, i0.z), f.x);
  const float c01 = lerp(at(i0.x, i0.y, i0.z + 1), at(i0.x + 1, i0.y, i0.z + 1), f.x);
  const float c11 = lerp(at(i0.x, i0.y + 1, i0.z + 1), at(i0.x + 1, i0.y + 1, i0.z + 1), f.x);
  return lerp(lerp(c00, c10, f.y), lerp(c01, c11, f.y), f.z);
}

// The box of non-zero voxels (per z slab, united in slab order).
VoxelBox nonZeroBox(const Volume& volume) {
  const glm::ivec3 d = volume.dims();
  std::vector<VoxelBox> slab(size_t(d.z));
  parallelFor(size_t(d.z), 4, [&](size_t, size_t z_begin, size_t z_end) {
    for (size_t z = z_begin; z < z_end; ++z) {
      VoxelBox box;
      for (int y = 0; y < d.y; ++y) {
        const float* row = volume.data() + volume.index(0, y, int(z));
        int lo = -1, hi = -1;
        for (int x = 0; x < d.x; ++x)
          if (row[x] != 0.0f) {
            if (lo < 0) lo = x;
            hi = x;
          }
        if (lo >= 0) box = box.unite({{lo, y, int(z)}, {hi + 1, y + 1, int(z) + 1}});
      }
      slab[z] = box;
    }
  });
  VoxelBox box;
  for (const VoxelBox& b : slab) box = box.unite(b);
  return box;
}

}  // namespace

WindSolver::WindSolver(glm::vec3 world_min, glm::vec3 world_max, const WindParams& params)
    : params_(params),
      world_min_(world_min),
      cell_((world_max - world_min) / glm::vec3(params.grid)) {
  const size_t n = size_t(params.grid.x) * params.grid.y * params.grid.z;
  velocity_.assign(n, glm::vec3(0));
  scratch_velocity_.assign(n, glm::vec3(0));
  divergence_.assign(n, 0.0f);
  pressure_.assign(n, 0.0f);
  scratch_pressure_.assign(n, 0.0f);
}

void WindSolver::setUniformWind(glm::vec3 velocity) {
  std::fill(velocity_.begin(), velocity_.end(), velocity);
}

void WindSolver::addForce(glm::vec3 force, glm::vec3 centre, float radius, float dt) {
  const glm::ivec3 n = params_.grid;
  for (int z = 0; z < n.z; ++z)
    for (int y = 0; y < n.y; ++y)
      for (int x = 0; x < n.x; ++x) {
        const glm::vec3 p = world_min_ + (glm::vec3(x, y, z) + 0.5f) * cell_;
        const float falloff = 1.0f - glm::distance(p, centre) / radius;
        if (falloff > 0) velocity_[index(x, y, z)] += dt * falloff * force;  // Eq. (3.5)
      }
}

glm::vec3 WindSolver::sampleVelocityInCells(glm::vec3 c) const {
  return sampleClamped(velocity_, params_.grid, c);
}

glm::vec3 WindSolver::sampleVelocity(glm::vec3 world) const {
  return sampleVelocityInCells((world - world_min_) / cell_ - 0.5f);
}

void WindSolver::divergence(std::vector<float>* out) const {
  const glm::ivec3 n = params_.grid;
  parallelFor(size_t(n.z), 4, [&](size_t, size_t z_begin, size_t z_end) {
    for (int z = int(z_begin); z < int(z_end); ++z)
      for (int y = 0; y < n.y; ++y)
        for (int x = 0; x < n.x; ++x) {
          // Central differences; the border repeats its cell (open, zero-gradient outflow).
          auto u = [&](int i, int j, int k) {
            return velocity_[index(std::clamp(i, 0, n.x - 1), std::clamp(j, 0, n.y - 1),
                                   std::clamp(k, 0, n.z - 1))];
          };
          (*out)[index(x, y, z)] = (u(x + 1, y, z).x - u(x - 1, y, z).x) / (2 * cell_.x) +
                                   (u(x, y + 1, z).y - u(x, y - 1, z).y) / (2 * cell_.y) +
                                   (u(x, y, z + 1).z - u(x, y, z - 1).z) / (2 * cell_.z);
        }
  });
}

float WindSolver::maxDivergence() const {
  std::vector<float> div(velocity_.size());
  divergence(&div);
  float m = 0;
  for (float d : div) m = std::max(m, std::abs(d));
  return m;
}

void WindSolver::project() {
  const glm::ivec3 n = params_.grid;
  divergence(&divergence_);
  // Jacobi sweeps on ∇²p = ∇·u (7-point Laplacian, p = 0 outside), from p = 0 each step so the
  // result depends on the velocity only.
  std::fill(pressure_.begin(), pressure_.end(), 0.0f);
  const glm::vec3 inv_h2 = 1.0f / (cell_ * cell_);
  const float diagonal = 2.0f * (inv_h2.x + inv_h2.y + inv_h2.z);
  for (int iteration = 0; iteration < params_.pressure_iterations; ++iteration) {
    parallelFor(size_t(n.z), 4, [&](size_t, size_t z_begin, size_t z_end) {
      auto p = [&](int i, int j, int k) {
        if (i < 0 || j < 0 || k < 0 || i >= n.x || j >= n.y || k >= n.z) return 0.0f;
        return pressure_[index(i, j, k)];
      };
      for (int z = int(z_begin); z < int(z_end); ++z)
        for (int y = 0; y < n.y; ++y)
          for (int x = 0; x < n.x; ++x) {
            const float neighbours = (p(x - 1, y, z) + p(x + 1, y, z)) * inv_h2.x +
                                     (p(x, y - 1, z) + p(x, y + 1, z)) * inv_h2.y +
                                     (p(x, y, z - 1) + p(x, y, z + 1)) * inv_h2.z;
            scratch_pressure_[index(x, y, z)] =
                (neighbours - divergence_[index(x, y, z)]) / diagonal;
          }
    });
    pressure_.swap(scratch_pressure_);
  }
  // u ← u − ∇p.
  parallelFor(size_t(n.z), 4, [&](size_t, size_t z_begin, size_t z_end) {
    auto p = [&](int i, int j, int k) {
      if (i < 0 || j < 0 || k < 0 || i >= n.x || j >= n.y || k >= n.z) return 0.0f;
      return pressure_[index(i, j, k)];
    };
    for (int z = int(z_begin); z < int(z_end); ++z)
      for (int y = 0; y < n.y; ++y)
        for (int x = 0; x < n.x; ++x)
          velocity_[index(x, y, z)] -= glm::vec3((p(x + 1, y, z) - p(x - 1, y, z)) / (2 * cell_.x),
                                                 (p(x, y + 1, z) - p(x, y - 1, z)) / (2 * cell_.y),
                                                 (p(x, y, z + 1) - p(x, y, z - 1)) / (2 * cell_.z));
  });
}

void WindSolver::stepVelocity(float dt) {
  const glm::ivec3 n = params_.grid;
  // Eq. (3.7) on u itself.
  parallelFor(size_t(n.z), 4, [&](size_t, size_t z_begin, size_t z_end) {
    for (int z = int(z_begin); z < int(z_end); ++z)
      for (int y = 0; y < n.y; ++y)
        for (int x = 0; x < n.x; ++x) {
          const glm::vec3 u = velocity_[index(x, y, z)];
          scratch_velocity_[index(x, y, z)] =
              sampleVelocityInCells(glm::vec3(x, y, z) - u * dt / cell_);
        }
  });
  velocity_.swap(scratch_velocity_);
  project();
}

VoxelBox WindSolver::advectDensity(float dt, Volume* density) {
  const glm::vec3 vs = density->voxelSize();
  glm::vec3 max_velocity(0);
  for (const glm::vec3& u : velocity_) max_velocity = glm::max(max_velocity, glm::abs(u));
  const glm::ivec3 reach = glm::ivec3(glm::ceil(max_velocity * dt / vs)) + 1;
  const VoxelBox occupied = nonZeroBox(*density);
  if (occupied.empty()) return {};
  // Outside this box a voxel is 0 and traces back to zeros only: it stays 0.
  const VoxelBox box =
      VoxelBox{occupied.lo - reach, occupied.hi + reach}.intersect(density->bounds());
  const glm::ivec3 size = box.hi - box.lo;
  scratch_density_.resize(size_t(size.x) * size.y * size.z);
  const float fade = std::exp(-params_.dissipation * dt);
  // Velocity in cells at a voxel centre: world = min + (v + 0.5)·vs; cells = world/cell − 0.5.
  const glm::vec3 voxel_to_cells = vs / cell_;
  const glm::vec3 offset_cells = 0.5f * voxel_to_cells - 0.5f;
  const glm::vec3 step_in_voxels = dt / vs;
  parallelFor(size_t(size.z), 2, [&](size_t, size_t z_begin, size_t z_end) {
    for (int z = int(z_begin); z < int(z_end); ++z)
      for (int y = 0; y < size.y; ++y)
        for (int x = 0; x < size.x; ++x) {
          const glm::ivec3 v = box.lo + glm::ivec3(x, y, z);
          const glm::vec3 u = sampleVelocityInCells(glm::vec3(v) * voxel_to_cells + offset_cells);
          const float rho = sampleDensity(*density, glm::vec3(v) - u * step_in_voxels);
          scratch_density_[(size_t(z) * size.y + y) * size.x + x] = rho * fade;
        }
  });
  parallelFor(size_t(size.z), 8, [&](size_t, size_t z_begin, size_t z_end) {
    for (int z = int(z_begin); z < int(z_end); ++z)
      for (int y = 0; y < size.y; ++y)
        std::copy_n(&scratch_density_[(size_t(z) * size.y + y) * size.x], size.x,
                    density->data() + density->index(box.lo.x, box.lo.y + y, box.lo.z + z));
  });
  density->markDirty(box);
  return box;
}

VoxelBox WindSolver::step(float dt, Volume* density) {
  stepVelocity(dt);
  return advectDensity(dt, density);
}

}  // namespace cb
