#include "app/tools/wind.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>

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
    return volume.at(x, y, z);
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
      std::vector<float> row(size_t(d.x));
      for (int y = 0; y < d.y; ++y) {
        volume.readLine({0, y, int(z)}, 0, d.x, row.data());
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
      // Rows of the neighbours; a row outside the grid reads zeros (p = 0 outside).
      const std::vector<float> zeros(size_t(n.x), 0.0f);
      auto row = [&](int j, int k) -> const float* {
        if (j < 0 || k < 0 || j >= n.y || k >= n.z) return zeros.data();
        return pressure_.data() + index(0, j, k);
      };
      for (int z = int(z_begin); z < int(z_end); ++z)
        for (int y = 0; y < n.y; ++y) {
          const float* c = row(y, z);
          const float *ym = row(y - 1, z), *yp = row(y + 1, z);
          const float *zm = row(y, z - 1), *zp = row(y, z + 1);
          const float* div = divergence_.data() + index(0, y, z);
          float* out = scratch_pressure_.data() + index(0, y, z);
          for (int x = 0; x < n.x; ++x) {
            const float xm = x > 0 ? c[x - 1] : 0.0f, xp = x + 1 < n.x ? c[x + 1] : 0.0f;
            const float neighbours =
                (xm + xp) * inv_h2.x + (ym[x] + yp[x]) * inv_h2.y + (zm[x] + zp[x]) * inv_h2.z;
            out[x] = (neighbours - div[x]) / diagonal;
          }
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

glm::ivec3 WindSolver::reachInVoxels(float dt, const Volume& density) const {
  glm::vec3 max_velocity(0);
  for (const glm::vec3& u : velocity_) max_velocity = glm::max(max_velocity, glm::abs(u));
  return glm::ivec3(glm::ceil(max_velocity * dt / density.voxelSize())) + 1;
}

VoxelBox WindSolver::advectDensity(float dt, Volume* density) {
  const glm::ivec3 d = density->dims();
  const glm::ivec3 blocks = (d + kBlock - 1) / kBlock;
  const size_t block_count = size_t(blocks.x) * blocks.y * blocks.z;
  auto block_index = [&](glm::ivec3 b) { return (size_t(b.z) * blocks.y + b.y) * blocks.x + b.x; };
  if (occupancy_instance_ != density->instanceId() ||
      occupancy_generation_ != density->generation() || block_occupied_.size() != block_count) {
    // One pass over the volume: which blocks hold density.
    block_occupied_.assign(block_count, 0);
    parallelFor(size_t(blocks.z), 1, [&](size_t, size_t bz_begin, size_t bz_end) {
      std::vector<float> row(size_t(d.x));
      for (int bz = int(bz_begin); bz < int(bz_end); ++bz)
        for (int z = bz * kBlock; z < std::min(d.z, (bz + 1) * kBlock); ++z)
          for (int y = 0; y < d.y; ++y) {
            density->readLine({0, y, z}, 0, d.x, row.data());
            for (int x = 0; x < d.x; ++x)
              if (row[x] != 0.0f) block_occupied_[block_index({x / kBlock, y / kBlock, bz})] = 1;
          }
    });
  }
  VoxelBox occupied;
  for (int bz = 0; bz < blocks.z; ++bz)
    for (int by = 0; by < blocks.y; ++by)
      for (int bx = 0; bx < blocks.x; ++bx)
        if (block_occupied_[block_index({bx, by, bz})])
          occupied = occupied.unite({glm::ivec3(bx, by, bz) * kBlock,
                                     glm::min(glm::ivec3(bx + 1, by + 1, bz + 1) * kBlock, d)});
  if (occupied.empty()) return {};
  const glm::vec3 vs = density->voxelSize();
  const glm::ivec3 reach = reachInVoxels(dt, *density);
  // A destination voxel backtraces at most `reach` voxels, and its interpolation reads one
  // more: it can be non-zero only if an occupied block lies within that many blocks.
  const glm::ivec3 reach_blocks = (reach + 1 + kBlock - 1) / kBlock;
  std::vector<uint8_t> live(block_count, 0);
  {
    // Separable max (dilation) over the block grid, x then y then z.
    std::vector<uint8_t> a = block_occupied_, b(block_count);
    for (int axis = 0; axis < 3; ++axis) {
      for (int bz = 0; bz < blocks.z; ++bz)
        for (int by = 0; by < blocks.y; ++by)
          for (int bx = 0; bx < blocks.x; ++bx) {
            const glm::ivec3 c(bx, by, bz);
            uint8_t m = 0;
            for (int k = -reach_blocks[axis]; k <= reach_blocks[axis] && !m; ++k) {
              glm::ivec3 q = c;
              q[axis] += k;
              if (q[axis] >= 0 && q[axis] < blocks[axis]) m = a[block_index(q)];
            }
            b[block_index(c)] = m;
          }
      a.swap(b);
    }
    live.swap(a);
  }
  const VoxelBox box =
      VoxelBox{occupied.lo - reach, occupied.hi + reach}.intersect(density->bounds());
  const glm::ivec3 size = box.hi - box.lo;
  scratch_density_.resize(size_t(size.x) * size.y * size.z);
  const float fade = std::exp(-params_.dissipation * dt);
  const glm::vec3 voxel_to_cells = vs / cell_;
  const glm::vec3 offset_cells = 0.5f * voxel_to_cells - 0.5f;
  const glm::vec3 step_in_voxels = dt / vs;
  // Which blocks the new density occupies: flags only ever set to 1, from any task.
  std::unique_ptr<std::atomic<uint8_t>[]> next_occupied(new std::atomic<uint8_t>[block_count]);
  for (size_t i = 0; i < block_count; ++i) next_occupied[i].store(0, std::memory_order_relaxed);
  parallelFor(size_t(size.z), 2, [&](size_t, size_t z_begin, size_t z_end) {
    for (int z = int(z_begin); z < int(z_end); ++z)
      for (int y = 0; y < size.y; ++y) {
        float* out = &scratch_density_[(size_t(z) * size.y + y) * size.x];
        const glm::ivec3 row = box.lo + glm::ivec3(0, y, z);
        for (int x = 0; x < size.x;) {
          const glm::ivec3 v = row + glm::ivec3(x, 0, 0);
          const glm::ivec3 blk = v / kBlock;
          const int run_end = std::min(size.x, (blk.x + 1) * kBlock - box.lo.x);
          if (!live[block_index(blk)]) {
            std::fill(out + x, out + run_end, 0.0f);
            x = run_end;
            continue;
          }
          bool any = false;
          for (; x < run_end; ++x) {
            const glm::ivec3 p = row + glm::ivec3(x, 0, 0);
            const glm::vec3 u = sampleVelocityInCells(glm::vec3(p) * voxel_to_cells + offset_cells);
            const float rho = sampleDensity(*density, glm::vec3(p) - u * step_in_voxels) * fade;
            out[x] = rho;
            any = any || rho != 0.0f;
          }
          if (any) next_occupied[block_index(blk)].store(1, std::memory_order_relaxed);
        }
      }
  });
  parallelFor(size_t(size.z), 8, [&](size_t, size_t z_begin, size_t z_end) {
    for (int z = int(z_begin); z < int(z_end); ++z)
      for (int y = 0; y < size.y; ++y)
        density->writeLine({box.lo.x, box.lo.y + y, box.lo.z + z}, 0, size.x,
                           &scratch_density_[(size_t(z) * size.y + y) * size.x]);
  });
  // Blocks outside the box kept their density; inside it they hold what was just written.
  for (int bz = 0; bz < blocks.z; ++bz)
    for (int by = 0; by < blocks.y; ++by)
      for (int bx = 0; bx < blocks.x; ++bx) {
        const glm::ivec3 lo = glm::ivec3(bx, by, bz) * kBlock;
        const VoxelBox block{lo, glm::min(lo + kBlock, d)};
        const size_t i = block_index({bx, by, bz});
        const uint8_t now = next_occupied[i].load(std::memory_order_relaxed);
        if (block.intersect(box) == block)
          block_occupied_[i] = now;  // wholly rewritten
        else if (!block.intersect(box).empty())
          block_occupied_[i] = block_occupied_[i] | now;  // partly: a superset is safe
      }
  density->markDirty(box);
  occupancy_instance_ = density->instanceId();
  occupancy_generation_ = density->generation();
  return box;
}

VoxelBox WindSolver::advectDensityEveryVoxel(float dt, Volume* density) {
  const glm::vec3 vs = density->voxelSize();
  const glm::ivec3 reach = reachInVoxels(dt, *density);
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
        density->writeLine({box.lo.x, box.lo.y + y, box.lo.z + z}, 0, size.x,
                           &scratch_density_[(size_t(z) * size.y + y) * size.x]);
  });
  density->markDirty(box);
  occupancy_instance_ = 0;  // the block occupancy was not kept
  return box;
}

VoxelBox WindSolver::step(float dt, Volume* density) {
  stepVelocity(dt);
  return advectDensity(dt, density);
}

}  // namespace cb
