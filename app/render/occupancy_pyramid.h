// Max-mip occupancy pyramid for lossless empty-space skipping (the role of the thesis's
// stackless octree, §4.4, as a mip pyramid that is cheap to update from dirty boxes).
//
// Level 0 has one cell per brick of kOccupancyBrick³ voxels; a cell is 1 if any voxel of its
// brick *dilated by one voxel* is non-zero, so a trilinear sample anywhere inside an empty cell
// reads only zero voxels and skipping it cannot change the image. Level m+1 is the max of 2×2×2
// cells of level m. Level dims are padded to powers of two so they match GL's mip chain; the
// padding cells are empty.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <new>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "app/volume/box.h"
#include "app/volume/volume.h"

namespace cb {

constexpr int kOccupancyBrick = 4;

// An allocator whose memory comes zeroed from the system (calloc) and which leaves
// value-initialised elements as they come: a level of n cells is made without writing them, so
// the pages of a large, mostly empty pyramid (16 MB at level 0 for a 1536×256×1536 sky) cost
// nothing until a cell in them is written or read. Only for trivially constructible T; a vector
// grown by resize() within its capacity gets whatever those bytes held (levels are made at
// their size and never resized).
template <class T>
struct ZeroedAllocator {
  using value_type = T;
  ZeroedAllocator() = default;
  template <class U>
  ZeroedAllocator(const ZeroedAllocator<U>&) noexcept {}
  T* allocate(size_t n) {
    if (void* p = std::calloc(n, sizeof(T))) return static_cast<T*>(p);
    throw std::bad_alloc();
  }
  void deallocate(T* p, size_t) noexcept { std::free(p); }
  template <class U>
  void construct(U*) noexcept {}  // value-initialisation: calloc's zeros stand
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  friend bool operator==(const ZeroedAllocator&, const ZeroedAllocator&) { return true; }
};
// One level's cells (x fastest; 1 = may hold density).
using OccupancyCells = std::vector<uint8_t, ZeroedAllocator<uint8_t>>;

struct OccupancyPyramid {
  int brick = kOccupancyBrick;
  glm::ivec3 volume_dims{0};
  std::vector<glm::ivec3> level_dims;  // level_dims[0] = pow2(ceil(volume_dims / brick))
  std::vector<OccupancyCells> levels;

  int levelCount() const { return int(levels.size()); }
  uint8_t at(int level, glm::ivec3 cell) const {
    const glm::ivec3 d = level_dims[size_t(level)];
    return levels[size_t(level)][(size_t(cell.z) * d.y + size_t(cell.y)) * d.x + size_t(cell.x)];
  }
  // Cell size in voxels at `level`.
  int cellSize(int level) const { return brick << level; }
};

// Allocates the pyramid for `volume`'s dims and computes every cell.
OccupancyPyramid buildOccupancy(const Volume& volume);

// The pyramid of `grown`, a volume whose bricks are those `pyramid` was built for moved by
// `voxel_offset` voxels (Volume::movedInto; whole level-0 cells) and empty sky around them,
// without looking at a voxel away from the old edge: each level whose cell size divides the
// offset is copied across shifted (its cells cover the same voxels), the others are reduced from
// the level below, and the cells along the old edge, whose dilated footprint now reaches into the
// grown sky, are recomputed (updateOccupancy). Equal to buildOccupancy(grown).
OccupancyPyramid shiftOccupancy(const OccupancyPyramid& pyramid, const Volume& grown,
                                glm::ivec3 voxel_offset);

// Recomputes the level-0 cells whose dilated footprint meets `dirty` (voxel box) and their
// ancestors. Returns the box of level-0 cells updated (empty if nothing was dirty); with
// `changed`, also whether any of them took a new value (an edit inside occupied cloud leaves the
// pyramid as it was). Parallel over z with cb::parallelFor; the result does not depend on the
// thread count.
VoxelBox updateOccupancy(OccupancyPyramid& pyramid, const Volume& volume, const VoxelBox& dirty,
                         bool* changed = nullptr);

// One rectangle of the boundary between occupied cells of a level and empty (or outside) ones:
// it lies in the plane `plane` (a cell coordinate) across `axis`, facing the empty side (side 1:
// towards +axis), and spans [u0, u1) × [v0, v1) cells on the axes u = axis + 1 and v = axis + 2
// (mod 3).
struct BoundaryRect {
  int axis, side, plane, u0, u1, v0, v1;
};

// The boundary of the occupied cells of `level`, coplanar faces merged into rectangles (runs
// along u, stacked along v): each cell face between an occupied cell and an empty or outside
// neighbour lies in exactly one rectangle, and no rectangle holds any other face.
std::vector<BoundaryRect> occupiedBoundaryRects(const OccupancyPyramid& pyramid, int level);

// How far (in cells) boundaryTriangles grows each rectangle in its plane. Merged rectangles meet
// their neighbours in T-junctions, where the rasteriser's snapping of the shared vertex could
// open a crack a pixel centre falls through; grown, neighbours overlap instead. The ray bounds
// pass keeps the nearest entry and the farthest exit, so overlap only widens the bounds
// (losslessly: a pixel or sample taken in empty space adds nothing).
constexpr float kBoundaryOverlap = 1.0f / 16.0f;

// The 4 corners of each rectangle (voxel coordinates: cells of `cell_size` voxels), grown by
// kBoundaryOverlap: corner k is at (u1 if k & 1 else u0, v1 if k & 2 else v0). The projection of
// the boundary lies inside their projected bounding rectangle.
std::vector<glm::vec3> boundaryCorners(const std::vector<BoundaryRect>& rects, float cell_size);

// Two triangles (6 vertices of boundaryCorners) per rectangle, wound counter-clockwise as seen from
// the empty side (front faces face away from occupied space).
std::vector<glm::vec3> boundaryTriangles(const std::vector<BoundaryRect>& rects, float cell_size);

// boundaryTriangles of occupiedBoundaryRects. Rasterised, it tells each pixel where its ray enters
// and leaves occupied space (see shaders/ray_bounds.*.glsl). llvmpipe sets triangles up on the
// calling thread, so that pass costs per triangle: merged, the bundled cumulus's boundary takes
// 12 thousand triangles instead of 34 thousand.
std::vector<glm::vec3> occupiedBoundaryFaces(const OccupancyPyramid& pyramid, int level);

// Is any cell of `level` within one cell of the voxel-space point `p` occupied? (When the eye is,
// rays must start at the near plane rather than at the nearest occupied face.)
bool occupiedNear(const OccupancyPyramid& pyramid, int level, glm::vec3 p);

}  // namespace cb
