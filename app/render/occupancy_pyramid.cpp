#include "app/render/occupancy_pyramid.h"

#include <algorithm>
#include <atomic>
#include <tuple>

#include "app/core/parallel_for.h"

namespace cb {
namespace {

int nextPowerOfTwo(int v) {
  int p = 1;
  while (p < v) p <<= 1;
  return p;
}

size_t cellIndex(glm::ivec3 d, int x, int y, int z) {
  return (size_t(z) * d.y + size_t(y)) * d.x + size_t(x);
}

// Is any voxel in the brick of `cell`, dilated by one voxel, non-zero?
uint8_t brickOccupied(const Volume& v, int brick, glm::ivec3 cell) {
  const glm::ivec3 dims = v.dims();
  glm::ivec3 lo = glm::max(cell * brick - 1, glm::ivec3(0));
  glm::ivec3 hi = glm::min(cell * brick + brick + 1, dims);
  // Unallocated bricks read zero: look only into allocated ones.
  const glm::ivec3 blo = lo >> Volume::kBrickShift, bhi = (hi - 1) >> Volume::kBrickShift;
  for (int bz = blo.z; bz <= bhi.z; ++bz)
    for (int by = blo.y; by <= bhi.y; ++by)
      for (int bx = blo.x; bx <= bhi.x; ++bx) {
        if (!v.brick({bx, by, bz})) continue;
        const VoxelBox box = v.brickBox({bx, by, bz}).intersect({lo, hi});
        for (int z = box.lo.z; z < box.hi.z; ++z)
          for (int y = box.lo.y; y < box.hi.y; ++y)
            for (int x = box.lo.x; x < box.hi.x; ++x)
              if (v.at(x, y, z) != 0.0f) return 1;
      }
  return 0;
}

// An empty pyramid for a volume of `dims`.
OccupancyPyramid emptyPyramid(glm::ivec3 dims) {
  OccupancyPyramid p;
  p.volume_dims = dims;
  glm::ivec3 d0 = (dims + p.brick - 1) / p.brick;
  glm::ivec3 d(nextPowerOfTwo(d0.x), nextPowerOfTwo(d0.y), nextPowerOfTwo(d0.z));
  for (;;) {
    p.level_dims.push_back(d);
    p.levels.emplace_back(size_t(d.x) * d.y * d.z);  // zeros, unwritten (ZeroedAllocator)
    if (d == glm::ivec3(1)) break;
    d = glm::max(d / 2, glm::ivec3(1));
  }
  return p;
}

// Level m's cells in `region` (cells of level m) as the max of their children at level m − 1.
void reduceLevel(OccupancyPyramid& p, int m, const VoxelBox& region) {
  const glm::ivec3 dc = p.level_dims[size_t(m - 1)], dp = p.level_dims[size_t(m)];
  const OccupancyCells& child = p.levels[size_t(m - 1)];
  OccupancyCells& parent = p.levels[size_t(m)];
  for (int z = region.lo.z; z < region.hi.z; ++z)
    for (int y = region.lo.y; y < region.hi.y; ++y)
      for (int x = region.lo.x; x < region.hi.x; ++x) {
        uint8_t v = 0;
        for (int k = 0; k < 8; ++k) {
          glm::ivec3 c = glm::ivec3(x, y, z) * 2 + glm::ivec3(k & 1, (k >> 1) & 1, k >> 2);
          if (c.x < dc.x && c.y < dc.y && c.z < dc.z) v |= child[cellIndex(dc, c.x, c.y, c.z)];
        }
        parent[cellIndex(dp, x, y, z)] = v;
      }
}

}  // namespace

OccupancyPyramid buildOccupancy(const Volume& volume) {
  OccupancyPyramid p = emptyPyramid(volume.dims());
  updateOccupancy(p, volume, volume.bounds());
  return p;
}

OccupancyPyramid shiftOccupancy(const OccupancyPyramid& old, const Volume& grown,
                                glm::ivec3 voxel_offset) {
  OccupancyPyramid p = emptyPyramid(grown.dims());
  const glm::ivec3 cell_offset = voxel_offset / p.brick;
  if (old.brick != p.brick || cell_offset * p.brick != voxel_offset || old.levelCount() == 0)
    return buildOccupancy(grown);
  for (int m = 0; m < p.levelCount(); ++m) {
    const glm::ivec3 d = p.level_dims[size_t(m)];
    const int size = 1 << m;
    if (m < old.levelCount() && cell_offset % size == glm::ivec3(0)) {
      // Cell c of the old level covers the voxels cell c + offset/size covers now.
      const glm::ivec3 at = cell_offset / size;
      const glm::ivec3 od = old.level_dims[size_t(m)];
      const glm::ivec3 n = glm::min(od, d - at);
      for (int z = 0; z < n.z; ++z)
        for (int y = 0; y < n.y; ++y)
          std::copy_n(
              old.levels[size_t(m)].begin() + std::ptrdiff_t(cellIndex(od, 0, y, z)),
              std::max(n.x, 0),
              p.levels[size_t(m)].begin() + std::ptrdiff_t(cellIndex(d, at.x, at.y + y, at.z + z)));
    } else {
      reduceLevel(p, m, {glm::ivec3(0), d});
    }
  }
  // The old edge's cells on both sides (a cell's footprint is dilated by one voxel): each face of
  // the old box that lies inside the grown one.
  const VoxelBox moved{voxel_offset, voxel_offset + old.volume_dims};
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int plane = side ? moved.hi[axis] : moved.lo[axis];
      if (plane <= 0 || plane >= grown.dims()[axis]) continue;
      VoxelBox slab{moved.lo - 1, moved.hi + 1};
      slab.lo[axis] = plane - 1;
      slab.hi[axis] = plane + 1;
      updateOccupancy(p, grown, slab);
    }
  return p;
}

VoxelBox updateOccupancy(OccupancyPyramid& p, const Volume& volume, const VoxelBox& dirty,
                         bool* changed) {
  if (changed) *changed = false;
  VoxelBox voxels = dirty.intersect(volume.bounds());
  if (voxels.empty()) return {};
  // Cells whose dilated brick [c*b-1, c*b+b+1) meets the dirty box.
  const glm::ivec3 real_cells = (volume.dims() + p.brick - 1) / p.brick;
  VoxelBox cells{glm::max((voxels.lo - 1) / p.brick, glm::ivec3(0)),
                 glm::min(voxels.hi / p.brick + 1, real_cells)};
  // (voxels.lo-1)/b rounds toward zero for lo = 0, which the max() above keeps at 0.
  {
    const glm::ivec3 d = p.level_dims[0];
    OccupancyCells& level = p.levels[0];
    std::atomic<bool> any_changed{false};
    parallelFor(size_t(cells.hi.z - cells.lo.z), 1, [&](size_t, size_t z0, size_t z1) {
      bool chunk_changed = false;
      for (int z = cells.lo.z + int(z0); z < cells.lo.z + int(z1); ++z)
        for (int y = cells.lo.y; y < cells.hi.y; ++y)
          for (int x = cells.lo.x; x < cells.hi.x; ++x) {
            uint8_t& cell = level[cellIndex(d, x, y, z)];
            const uint8_t occupied = brickOccupied(volume, p.brick, {x, y, z});
            chunk_changed |= cell != occupied;
            cell = occupied;
          }
      if (chunk_changed) any_changed.store(true, std::memory_order_relaxed);
    });
    if (changed) *changed = any_changed.load();
  }
  // Max-reduce the touched region up the pyramid.
  VoxelBox region = cells;
  for (int m = 1; m < p.levelCount(); ++m) {
    region = {region.lo / 2, glm::min((region.hi + 1) / 2, p.level_dims[size_t(m)])};
    reduceLevel(p, m, region);
  }
  return cells;
}

std::vector<BoundaryRect> occupiedBoundaryRects(const OccupancyPyramid& p, int level) {
  const glm::ivec3 d = p.level_dims[size_t(level)];
  auto occupied = [&](glm::ivec3 c) {
    return c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x < d.x && c.y < d.y && c.z < d.z &&
           p.at(level, c) != 0;
  };
  // Every face between an occupied cell and an empty or outside neighbour, as a 1×1 rectangle.
  // Cells are visited under the occupied cells of a coarser level only (max-mip: an empty coarse
  // cell has no occupied cell below it); a sky is mostly empty.
  const int coarse = std::min(level + 2, p.levelCount() - 1);
  const int per = 1 << (coarse - level);  // cells of `level` across a coarse cell
  const glm::ivec3 dc = p.level_dims[size_t(coarse)];
  std::vector<BoundaryRect> faces;
  for (int cz = 0; cz < dc.z; ++cz)
    for (int cy = 0; cy < dc.y; ++cy)
      for (int cx = 0; cx < dc.x; ++cx) {
        if (p.at(coarse, {cx, cy, cz}) == 0) continue;
        const glm::ivec3 lo = glm::ivec3(cx, cy, cz) * per;
        const glm::ivec3 hi = glm::min(lo + per, d);
        for (int z = lo.z; z < hi.z; ++z)
          for (int y = lo.y; y < hi.y; ++y)
            for (int x = lo.x; x < hi.x; ++x) {
              const glm::ivec3 c(x, y, z);
              if (!occupied(c)) continue;
              for (int axis = 0; axis < 3; ++axis)
                for (int side = 0; side < 2; ++side) {
                  glm::ivec3 n = c;
                  n[axis] += side ? 1 : -1;
                  if (occupied(n)) continue;
                  const int u = c[(axis + 1) % 3], v = c[(axis + 2) % 3];
                  faces.push_back({axis, side, c[axis] + side, u, u + 1, v, v + 1});
                }
            }
      }
  // Runs along u, then runs of the same u extent stacked along v (a fixed order: the result
  // does not depend on anything but the occupancy).
  auto plane = [](const BoundaryRect& r) { return std::tie(r.axis, r.side, r.plane); };
  std::sort(faces.begin(), faces.end(), [&](const BoundaryRect& a, const BoundaryRect& b) {
    return std::tuple_cat(plane(a), std::tie(a.v0, a.u0)) <
           std::tuple_cat(plane(b), std::tie(b.v0, b.u0));
  });
  std::vector<BoundaryRect> runs;
  for (const BoundaryRect& f : faces) {
    if (!runs.empty() && plane(runs.back()) == plane(f) && runs.back().v0 == f.v0 &&
        runs.back().u1 == f.u0)
      runs.back().u1 = f.u1;
    else
      runs.push_back(f);
  }
  std::sort(runs.begin(), runs.end(), [&](const BoundaryRect& a, const BoundaryRect& b) {
    return std::tuple_cat(plane(a), std::tie(a.u0, a.u1, a.v0)) <
           std::tuple_cat(plane(b), std::tie(b.u0, b.u1, b.v0));
  });
  std::vector<BoundaryRect> rects;
  for (const BoundaryRect& r : runs) {
    if (!rects.empty() && plane(rects.back()) == plane(r) && rects.back().u0 == r.u0 &&
        rects.back().u1 == r.u1 && rects.back().v1 == r.v0)
      rects.back().v1 = r.v1;
    else
      rects.push_back(r);
  }
  return rects;
}

std::vector<glm::vec3> boundaryCorners(const std::vector<BoundaryRect>& rects, float cell_size) {
  std::vector<glm::vec3> out;
  out.reserve(rects.size() * 4);
  for (const BoundaryRect& r : rects) {
    const int u = (r.axis + 1) % 3, v = (r.axis + 2) % 3;
    for (int k = 0; k < 4; ++k) {
      glm::vec3 q(0.0f);
      q[r.axis] = float(r.plane);
      q[u] = (k & 1) ? float(r.u1) + kBoundaryOverlap : float(r.u0) - kBoundaryOverlap;
      q[v] = (k >> 1) ? float(r.v1) + kBoundaryOverlap : float(r.v0) - kBoundaryOverlap;
      out.push_back(q * cell_size);
    }
  }
  return out;
}

std::vector<glm::vec3> boundaryTriangles(const std::vector<BoundaryRect>& rects, float cell_size) {
  const std::vector<glm::vec3> corners = boundaryCorners(rects, cell_size);
  std::vector<glm::vec3> out;
  out.reserve(rects.size() * 6);
  for (size_t i = 0; i < rects.size(); ++i) {
    const glm::vec3* corner = &corners[i * 4];
    // Counter-clockwise seen from outside the occupied cell (from the empty side), so front
    // faces are where rays enter occupied space and back faces where they leave. Corners 0, 1, 3
    // turn counter-clockwise about +axis (u × v = axis).
    if (rects[i].side)
      for (int k : {0, 1, 3, 0, 3, 2}) out.push_back(corner[k]);
    else
      for (int k : {0, 3, 1, 0, 2, 3}) out.push_back(corner[k]);
  }
  return out;
}

std::vector<glm::vec3> occupiedBoundaryFaces(const OccupancyPyramid& p, int level) {
  return boundaryTriangles(occupiedBoundaryRects(p, level), float(p.cellSize(level)));
}

bool occupiedNear(const OccupancyPyramid& p, int level, glm::vec3 point) {
  const glm::ivec3 d = p.level_dims[size_t(level)];
  const glm::ivec3 c = glm::ivec3(glm::floor(point / float(p.cellSize(level))));
  for (int z = c.z - 1; z <= c.z + 1; ++z)
    for (int y = c.y - 1; y <= c.y + 1; ++y)
      for (int x = c.x - 1; x <= c.x + 1; ++x)
        if (x >= 0 && y >= 0 && z >= 0 && x < d.x && y < d.y && z < d.z && p.at(level, {x, y, z}))
          return true;
  return false;
}

}  // namespace cb
