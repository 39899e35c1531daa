// The wind's inner loops (wind.h): the semi-Lagrangian backtrace of a row of cells, a row of a
// Jacobi sweep, the flow map's displacement at the voxels of a block and the trilinear read of
// the starting density for a row of voxels. Each has an AVX2 version, used when the CPU has it,
// that does every lane's arithmetic in the scalar order (a + (b − a)·t lerps in x, then y, then
// z; separate multiplies and adds, no FMA; glm's clamp as max then min with its operand order),
// so both give the same bits and the bytes do not depend on the CPU.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "app/tools/huge_page_allocator.h"
#include "app/volume/box.h"
#include "app/volume/volume.h"

namespace cb::wind {

// a + (b − a)·t: exactly a at t = 0, so a zero displacement reproduces the input bit for bit.
template <typename T>
T lerp(T a, T b, float t) {
  return a + (b - a) * t;
}

// The trilinear blend of the eight values at(i0 + (0|1, 0|1, 0|1)) with weights f: the x lerps,
// then y, then z (the order every trilinear read of the wind keeps, so the bits agree).
template <typename At>
float trilinear(const At& at, glm::ivec3 i0, glm::vec3 f) {
  const float c00 = lerp(at(i0.x, i0.y, i0.z), at(i0.x + 1, i0.y, i0.z), f.x);
  const float c10 = lerp(at(i0.x, i0.y + 1, i0.z), at(i0.x + 1, i0.y + 1, i0.z), f.x);
  const float c01 = lerp(at(i0.x, i0.y, i0.z + 1), at(i0.x + 1, i0.y, i0.z + 1), f.x);
  const float c11 = lerp(at(i0.x, i0.y + 1, i0.z + 1), at(i0.x + 1, i0.y + 1, i0.z + 1), f.x);
  return lerp(lerp(c00, c10, f.y), lerp(c01, c11, f.y), f.z);
}

// False makes every kernel take its scalar version (the tests compare both); true (the default)
// uses AVX2 where the CPU has it.
void allowAvx2(bool allow);

// Trilinear sample of a cell grid (n cells, x fastest) at continuous index c (cell centres at
// integers), clamped to the border cells.
glm::vec3 sampleClamped(const glm::vec3* grid, glm::ivec3 n, glm::vec3 c);

// Row (y, z) of cells traced back through their velocities u[x] (world units per second) over
// dt: out[x] = sampleClamped(grid, n, (x, y, z) − u[x]·dt / cell), minus u[x]·dt when
// `minus_step` (the flow map's step). out must not alias grid.
void backtraceRow(const glm::vec3* grid, glm::ivec3 n, int y, int z, const glm::vec3* u, float dt,
                  glm::vec3 cell, bool minus_step, glm::vec3* out);

// One row of a Jacobi sweep on ∇²p = div (7-point Laplacian, p = 0 outside): for the row `p`
// and its neighbour rows, out[x] = ((p[x−1] + p[x+1])·inv_h2.x + (ym[x] + yp[x])·inv_h2.y +
// (zm[x] + zp[x])·inv_h2.z − div[x]) / diagonal, with p[−1] = p[count] = 0.
struct JacobiRow {
  const float *p, *ym, *yp, *zm, *zp, *div;
  float* out;
};
void jacobiRow(const JacobiRow& row, int count, glm::vec3 inv_h2, float diagonal);

// One row of the velocity's divergence by central differences, the border repeating its cell:
// out[x] = (u[x+1].x − u[x−1].x) / two_h.x + (yp[x].y − ym[x].y) / two_h.y +
// (zp[x].z − zm[x].z) / two_h.z, with u[−1] = u[0] and u[count] = u[count − 1] (ym … zp are the
// neighbour rows, clamped to the grid).
struct DivergenceRow {
  const glm::vec3 *u, *ym, *yp, *zm, *zp;
  float* out;
};
void divergenceRow(const DivergenceRow& row, int count, glm::vec3 two_h);

// One row of u ← u − ∇p by central differences, p = 0 outside: u[x] −= ((p[x+1] − p[x−1]) /
// two_h.x, (yp[x] − ym[x]) / two_h.y, (zp[x] − zm[x]) / two_h.z), p[−1] = p[count] = 0.
struct GradientRow {
  const float *p, *ym, *yp, *zm, *zp;
  glm::vec3* u;
};
void subtractGradientRow(const GradientRow& row, int count, glm::vec3 two_h);

// The componentwise range of the cells lo … hi (inclusive) of a grid (n cells, x fastest):
// glm::min and glm::max from +∞ and −∞ over the cells in z, y, x order.
void cellRange(const glm::vec3* grid, glm::ivec3 n, glm::ivec3 lo, glm::ivec3 hi, glm::vec3* min,
               glm::vec3* max);

// The resampling's blocks: kBlock voxels along each axis.
constexpr int kBlock = 8;
constexpr int kBlockVoxels = kBlock * kBlock * kBlock;

// A block's displacements, one array per component, voxel (x, y, z) of the block at
// ((z − lo.z)·kBlock + y − lo.y)·kBlock + x − lo.x.
struct BlockDisplacement {
  alignas(32) float d[3][kBlockVoxels];
};

// sampleClamped of a cell grid at voxel centres, v·voxel_to_cells + offset for voxel v. The
// per-axis part (clamp, cell and weight) is computed once per axis, and a block's samples are
// interpolated by axis: the x lerps once per pair of cell rows the block reads, the y lerps once
// per cell layer, then the z lerp per voxel; the same lerps of the same values as sampleClamped,
// so the same bits.
class VoxelCellSampler {
 public:
  VoxelCellSampler(const std::vector<glm::vec3>& grid, glm::ivec3 cells, glm::ivec3 voxels,
                   glm::vec3 voxel_to_cells, glm::vec3 offset);
  // The samples at the voxels of `block` (at most kBlock voxels along each axis).
  void block(const VoxelBox& block, BlockDisplacement* out) const;

 private:
  struct Taps {
    std::vector<int> i0, i1;
    std::vector<float> f;
  };
  const std::vector<glm::vec3>& grid_;
  glm::ivec3 cells_;
  Taps taps_[3];
};

// A volume's voxels in a dense array with a border of one zero voxel on every side, so the
// trilinear read of a sample whose eight voxels lie within the border needs no bounds checks.
class PaddedDense {
 public:
  explicit PaddedDense(const Volume& volume);

  // Trilinear density at continuous voxel index v (voxel centres at integers); 0 outside. The
  // arithmetic of the solver's sampleDensity on the volume itself, so the same bits.
  float sample(glm::vec3 v) const;
  // Voxels x0 … x0 + count − 1 of row (y, z), each displaced by (dx, dy, dz)[i] world units:
  // out[i] = sample((x0 + i, y, z) + d / voxel_size) · fade. True when any is not 0.
  bool sampleRow(int x0, int y, int z, int count, const float* dx, const float* dy, const float* dz,
                 glm::vec3 voxel_size, float fade, float* out) const;

 private:
  // Voxel (x, y, z) of the volume, −1 ≤ x, y, z ≤ dims.
  size_t index(int x, int y, int z) const {
    return (size_t(z + 1) * padded_.y + size_t(y + 1)) * padded_.x + size_t(x + 1);
  }
  glm::ivec3 dims_, padded_;
  HugePageVector<float> voxels_;
};

}  // namespace cb::wind
