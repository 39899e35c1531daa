#include "app/tools/wind.h"

#include <algorithm>
#include <cmath>

#include "app/core/parallel_for.h"
#include "app/tools/tool_error.h"
#include "app/tools/wind_kernels.h"

namespace cb {
namespace {

using wind::lerp;

// Trilinear density at continuous voxel index v (voxel centres at integers); 0 outside.
float sampleDensity(const Volume& volume, glm::vec3 v) {
  const glm::ivec3 d = volume.dims();
  const glm::ivec3 i0 = glm::ivec3(glm::floor(v));
  const glm::vec3 f = v - glm::vec3(i0);
  auto at = [&](int x, int y, int z) {
    if (x < 0 || y < 0 || z < 0 || x >= d.x || y >= d.y || z >= d.z) return 0.0f;
    return volume.at(x, y, z);
  };
  return wind::trilinear(at, i0, f);
}

// The box of non-zero voxels (per z slab, united in slab order).
VoxelBox nonZeroBox(const Volume& volume) {
  const glm::ivec3 d = volume.dims();
  std::vector<VoxelBox> slab(size_t(d.z));
  parallelFor(size_t(d.z), 4, [&](size_t, size_t z_begin, size_t z_end) {
    std::vector<float> row(size_t(d.x));
    for (size_t z = z_begin; z < z_end; ++z) {
      VoxelBox box;
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

// Which blocks (kBlock voxels on a side) of a volume hold density, as a summed-volume table for
// box queries.
class OccupiedBlocks {
 public:
  OccupiedBlocks(const Volume& start, int block) : blocks_((start.dims() + block - 1) / block) {
    const glm::ivec3 d = start.dims();
    const glm::ivec3 blocks = blocks_;
    auto block_index = [&](glm::ivec3 b) {
      return (size_t(b.z) * blocks.y + b.y) * blocks.x + b.x;
    };
    std::vector<uint8_t> occupied(size_t(blocks.x) * blocks.y * blocks.z, 0);
    parallelFor(size_t(blocks.z), 1, [&](size_t, size_t bz_begin, size_t bz_end) {
      std::vector<float> row(size_t(d.x));
      for (int bz = int(bz_begin); bz < int(bz_end); ++bz)
        for (int z = bz * block; z < std::min(d.z, (bz + 1) * block); ++z)
          for (int y = 0; y < d.y; ++y) {
            start.readLine({0, y, z}, 0, d.x, row.data());
            for (int x = 0; x < d.x; ++x)
              if (row[x] != 0.0f) occupied[block_index({x / block, y / block, bz})] = 1;
          }
    });
    const glm::ivec3 t = blocks + 1;
    table_.assign(size_t(t.x) * t.y * t.z, 0);
    for (int z = 1; z < t.z; ++z)
      for (int y = 1; y < t.y; ++y)
        for (int x = 1; x < t.x; ++x)
          at(x, y, z) = occupied[block_index({x - 1, y - 1, z - 1})] + at(x - 1, y, z) +
                        at(x, y - 1, z) + at(x, y, z - 1) - at(x - 1, y - 1, z) -
                        at(x - 1, y, z - 1) - at(x, y - 1, z - 1) + at(x - 1, y - 1, z - 1);
  }

  // Whether any of the blocks [lo, hi) holds density.
  bool any(glm::ivec3 lo, glm::ivec3 hi) const {
    lo = glm::max(lo, glm::ivec3(0));
    hi = glm::min(hi, blocks_);
    if (glm::any(glm::lessThanEqual(hi, lo))) return false;
    const int64_t sum = int64_t(at(hi.x, hi.y, hi.z)) - at(lo.x, hi.y, hi.z) -
                        at(hi.x, lo.y, hi.z) - at(hi.x, hi.y, lo.z) + at(lo.x, lo.y, hi.z) +
                        at(lo.x, hi.y, lo.z) + at(hi.x, lo.y, lo.z) - at(lo.x, lo.y, lo.z);
    return sum > 0;
  }

 private:
  uint32_t& at(int x, int y, int z) { return table_[index(x, y, z)]; }
  uint32_t at(int x, int y, int z) const { return table_[index(x, y, z)]; }
  size_t index(int x, int y, int z) const {
    const glm::ivec3 t = blocks_ + 1;
    return (size_t(z) * t.y + y) * t.x + x;
  }

  glm::ivec3 blocks_;
  std::vector<uint32_t> table_;
};

}  // namespace

struct WindSolver::StartCopy {
  static constexpr int kBlock = wind::kBlock;  // resampleDensity's blocks
  StartCopy(const Volume& start)
      : instance(start.instanceId()),
        generation(start.generation()),
        dense(start),
        occupied(start, kBlock) {}
  uint64_t instance, generation;
  wind::PaddedDense dense;
  OccupiedBlocks occupied;  // which kBlock³ blocks of the start hold density
};

const WindSolver::StartCopy& WindSolver::startCopy(const Volume& start) const {
  if (!start_copy_ || start_copy_->instance != start.instanceId() ||
      start_copy_->generation != start.generation())
    start_copy_ = std::make_shared<const StartCopy>(start);
  return *start_copy_;
}

WindSolver::WindSolver(glm::vec3 world_min, glm::vec3 world_max, const WindParams& params)
    : params_(params),
      world_min_(world_min),
      cell_((world_max - world_min) / glm::vec3(params.grid)) {
  const size_t n = size_t(params.grid.x) * params.grid.y * params.grid.z;
  velocity_.assign(n, glm::vec3(0));
  scratch_velocity_.assign(n, glm::vec3(0));
  displacement_.assign(n, glm::vec3(0));
  scratch_displacement_.assign(n, glm::vec3(0));
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
  return wind::sampleClamped(velocity_.data(), params_.grid, c);
}

glm::vec3 WindSolver::sampleVelocity(glm::vec3 world) const {
  return sampleVelocityInCells((world - world_min_) / cell_ - 0.5f);
}

void WindSolver::divergence(std::vector<float>* out, std::vector<float>* first_sweep) const {
  const glm::ivec3 n = params_.grid;
  const glm::vec3 inv_h2 = 1.0f / (cell_ * cell_);
  const float diagonal = 2.0f * (inv_h2.x + inv_h2.y + inv_h2.z);
  parallelFor(size_t(n.z), 4, [&](size_t, size_t z_begin, size_t z_end) {
    // Central differences; the border repeats its cell (open, zero-gradient outflow).
    auto row = [&](int j, int k) {
      return &velocity_[index(0, std::clamp(j, 0, n.y - 1), std::clamp(k, 0, n.z - 1))];
    };
    const std::vector<float> zeros(first_sweep ? size_t(n.x) : 0, 0.0f);
    for (int z = int(z_begin); z < int(z_end); ++z)
      for (int y = 0; y < n.y; ++y) {
        float* div = out->data() + index(0, y, z);
        wind::divergenceRow(
            {row(y, z), row(y - 1, z), row(y + 1, z), row(y, z - 1), row(y, z + 1), div}, n.x,
            2.0f * cell_);
        if (!first_sweep) continue;
        const float* p = zeros.data();
        wind::jacobiRow({p, p, p, p, p, div, first_sweep->data() + index(0, y, z)}, n.x, inv_h2,
                        diagonal);
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
  // Jacobi sweeps on ∇²p = ∇·u (7-point Laplacian, p = 0 outside), from p = 0 each step so the
  // result depends on the velocity only. The first sweep, whose neighbours are all 0, needs only
  // the cell's divergence and is made with it.
  if (params_.pressure_iterations > 0) {
    divergence(&divergence_, &scratch_pressure_);
    pressure_.swap(scratch_pressure_);
  } else {
    std::fill(pressure_.begin(), pressure_.end(), 0.0f);
  }
  const glm::vec3 inv_h2 = 1.0f / (cell_ * cell_);
  const float diagonal = 2.0f * (inv_h2.x + inv_h2.y + inv_h2.z);
  for (int iteration = 1; iteration < params_.pressure_iterations; ++iteration) {
    parallelFor(size_t(n.z), 4, [&](size_t, size_t z_begin, size_t z_end) {
      // Rows of the neighbours; a row outside the grid reads zeros (p = 0 outside).
      const std::vector<float> zeros(size_t(n.x), 0.0f);
      auto row = [&](int j, int k) -> const float* {
        if (j < 0 || k < 0 || j >= n.y || k >= n.z) return zeros.data();
        return pressure_.data() + index(0, j, k);
      };
      for (int z = int(z_begin); z < int(z_end); ++z)
        for (int y = 0; y < n.y; ++y)
          wind::jacobiRow(
              {row(y, z), row(y - 1, z), row(y + 1, z), row(y, z - 1), row(y, z + 1),
               divergence_.data() + index(0, y, z), scratch_pressure_.data() + index(0, y, z)},
              n.x, inv_h2, diagonal);
    });
    pressure_.swap(scratch_pressure_);
  }
  // u ← u − ∇p.
  parallelFor(size_t(n.z), 4, [&](size_t, size_t z_begin, size_t z_end) {
    // Rows of the neighbours; a row outside the grid reads zeros (p = 0 outside).
    const std::vector<float> zeros(size_t(n.x), 0.0f);
    auto row = [&](int j, int k) -> const float* {
      if (j < 0 || k < 0 || j >= n.y || k >= n.z) return zeros.data();
      return pressure_.data() + index(0, j, k);
    };
    for (int z = int(z_begin); z < int(z_end); ++z)
      for (int y = 0; y < n.y; ++y)
        wind::subtractGradientRow({row(y, z), row(y - 1, z), row(y + 1, z), row(y, z - 1),
                                   row(y, z + 1), &velocity_[index(0, y, z)]},
                                  n.x, 2.0f * cell_);
  });
}

void WindSolver::stepVelocity(float dt) {
  const glm::ivec3 n = params_.grid;
  // Eq. (3.7) on u itself.
  parallelFor(size_t(n.z), 4, [&](size_t, size_t z_begin, size_t z_end) {
    for (int z = int(z_begin); z < int(z_end); ++z)
      for (int y = 0; y < n.y; ++y)
        wind::backtraceRow(velocity_.data(), n, y, z, &velocity_[index(0, y, z)], dt, cell_, false,
                           &scratch_velocity_[index(0, y, z)]);
  });
  velocity_.swap(scratch_velocity_);
  project();
}

glm::ivec3 WindSolver::reachInVoxels(float dt, const Volume& density) const {
  glm::vec3 max_velocity(0);
  for (const glm::vec3& u : velocity_) max_velocity = glm::max(max_velocity, glm::abs(u));
  return glm::ivec3(glm::ceil(max_velocity * dt / density.voxelSize())) + 1;
}

void WindSolver::advectFlowMap(float dt) {
  const glm::ivec3 n = params_.grid;
  // D(x) ← D(x − u(x)·dt) − u(x)·dt: the air at x came from x − u·dt one step ago, and from
  // there back to the start by the displacement found there.
  parallelFor(size_t(n.z), 4, [&](size_t, size_t z_begin, size_t z_end) {
    for (int z = int(z_begin); z < int(z_end); ++z)
      for (int y = 0; y < n.y; ++y)
        wind::backtraceRow(displacement_.data(), n, y, z, &velocity_[index(0, y, z)], dt, cell_,
                           true, &scratch_displacement_[index(0, y, z)]);
  });
  displacement_.swap(scratch_displacement_);
  elapsed_ += dt;
}

void WindSolver::step(float dt) {
  stepVelocity(dt);
  advectFlowMap(dt);
}

VoxelBox WindSolver::resampleDensity(const Volume& start, Volume* out, const VoxelBox& previous,
                                     bool every_block) const {
  if (out->dims() != start.dims() || out->worldMin() != start.worldMin() ||
      out->worldMax() != start.worldMax())
    throw ToolError(ToolErrorKind::kMismatchedVolumes,
                    "wind: the density shown must have the starting density's dims and box");
  constexpr int kBlock = StartCopy::kBlock;
  const StartCopy& copy = startCopy(start);
  const glm::ivec3 d = start.dims(), n = params_.grid;
  const glm::ivec3 blocks = (d + kBlock - 1) / kBlock;
  auto block_index = [&](glm::ivec3 b) { return (size_t(b.z) * blocks.y + b.y) * blocks.x + b.x; };
  const size_t block_count = size_t(blocks.x) * blocks.y * blocks.z;
  auto anyOccupied = [&](glm::ivec3 lo, glm::ivec3 hi) { return copy.occupied.any(lo, hi); };
  const glm::vec3 vs = start.voxelSize();
  const glm::vec3 voxel_to_cells = vs / cell_;
  const glm::vec3 offset_cells = 0.5f * voxel_to_cells - 0.5f;
  const float fade = float(std::exp(-double(params_.dissipation) * elapsed_));
  // A destination block is live when the samples of its voxels can reach an occupied block:
  // the displacement there is a convex combination of the cells it interpolates, so its range
  // bounds where they land (one more voxel for the trilinear read).
  std::vector<uint8_t> live(block_count, 0), nonzero(block_count, 0);
  parallelFor(size_t(blocks.z), 1, [&](size_t, size_t bz_begin, size_t bz_end) {
    for (int bz = int(bz_begin); bz < int(bz_end); ++bz)
      for (int by = 0; by < blocks.y; ++by)
        for (int bx = 0; bx < blocks.x; ++bx) {
          const glm::ivec3 lo = glm::ivec3(bx, by, bz) * kBlock;
          const glm::ivec3 hi = glm::min(lo + kBlock, d);
          const glm::vec3 c_lo = glm::clamp(glm::vec3(lo) * voxel_to_cells + offset_cells,
                                            glm::vec3(0), glm::vec3(n - 1));
          const glm::vec3 c_hi = glm::clamp(glm::vec3(hi - 1) * voxel_to_cells + offset_cells,
                                            glm::vec3(0), glm::vec3(n - 1));
          const glm::ivec3 k_lo = glm::ivec3(glm::floor(c_lo)),
                           k_hi = glm::min(glm::ivec3(glm::floor(c_hi)) + 1, n - 1);
          glm::vec3 d_min, d_max;
          wind::cellRange(displacement_.data(), n, k_lo, k_hi, &d_min, &d_max);
          const glm::ivec3 src_lo = glm::ivec3(glm::floor(glm::vec3(lo) + d_min / vs)) - 1;
          const glm::ivec3 src_hi = glm::ivec3(glm::floor(glm::vec3(hi - 1) + d_max / vs)) + 2;
          live[block_index({bx, by, bz})] =
              every_block ||
              anyOccupied(glm::ivec3(glm::floor(glm::vec3(src_lo) / float(kBlock))),
                          glm::ivec3(glm::floor(glm::vec3(src_hi - 1) / float(kBlock))) + 1);
        }
  });
  const VoxelBox cleared = previous.intersect(out->bounds());
  const wind::VoxelCellSampler flow(displacement_, n, d, voxel_to_cells, offset_cells);
  const std::vector<float> zeros(size_t(kBlock), 0.0f);
  parallelFor(size_t(blocks.z), 1, [&](size_t, size_t bz_begin, size_t bz_end) {
    wind::BlockDisplacement disp;
    float row[kBlock];
    for (int bz = int(bz_begin); bz < int(bz_end); ++bz)
      for (int by = 0; by < blocks.y; ++by)
        for (int bx = 0; bx < blocks.x; ++bx) {
          const glm::ivec3 lo = glm::ivec3(bx, by, bz) * kBlock;
          const VoxelBox block{lo, glm::min(lo + kBlock, d)};
          const size_t b = block_index({bx, by, bz});
          if (!live[b]) {
            const VoxelBox clear = block.intersect(cleared);
            for (int z = clear.lo.z; z < clear.hi.z; ++z)
              for (int y = clear.lo.y; y < clear.hi.y; ++y)
                out->writeLine({clear.lo.x, y, z}, 0, clear.hi.x - clear.lo.x, zeros.data());
            continue;
          }
          flow.block(block, &disp);
          bool any = false;
          for (int z = block.lo.z; z < block.hi.z; ++z)
            for (int y = block.lo.y; y < block.hi.y; ++y) {
              const int at = ((z - lo.z) * kBlock + y - lo.y) * kBlock;
              const int width = block.hi.x - block.lo.x;
              any = copy.dense.sampleRow(lo.x, y, z, width, disp.d[0] + at, disp.d[1] + at,
                                         disp.d[2] + at, vs, fade, row) ||
                    any;
              out->writeLine({block.lo.x, y, z}, 0, width, row);
            }
          nonzero[b] = any;
        }
  });
  VoxelBox written;
  for (int bz = 0; bz < blocks.z; ++bz)
    for (int by = 0; by < blocks.y; ++by)
      for (int bx = 0; bx < blocks.x; ++bx)
        if (nonzero[block_index({bx, by, bz})]) {
          const glm::ivec3 lo = glm::ivec3(bx, by, bz) * kBlock;
          written = written.unite({lo, glm::min(lo + kBlock, d)});
        }
  VoxelBox dirty = written.unite(cleared);
  for (size_t b = 0; b < block_count; ++b)
    if (live[b]) {
      const glm::ivec3 bi(int(b % blocks.x), int((b / blocks.x) % blocks.y),
                          int(b / (size_t(blocks.x) * blocks.y)));
      const glm::ivec3 lo = bi * kBlock;
      dirty = dirty.unite({lo, glm::min(lo + kBlock, d)});
    }
  if (!dirty.empty()) out->markDirty(dirty);
  return written;
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
  return box;
}

}  // namespace cb
