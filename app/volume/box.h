// Integer voxel boxes (half-open: lo inclusive, hi exclusive), used for dirty regions.
#pragma once

#include <glm/glm.hpp>

namespace cb {

struct VoxelBox {
  glm::ivec3 lo{0};
  glm::ivec3 hi{0};

  bool empty() const { return hi.x <= lo.x || hi.y <= lo.y || hi.z <= lo.z; }
  long long voxelCount() const {
    return empty() ? 0 : (long long)(hi.x - lo.x) * (hi.y - lo.y) * (hi.z - lo.z);
  }
  bool contains(glm::ivec3 p) const {
    return glm::all(glm::greaterThanEqual(p, lo)) && glm::all(glm::lessThan(p, hi));
  }
  // Smallest box holding both (an empty box is the identity).
  VoxelBox unite(const VoxelBox& o) const {
    if (empty()) return o;
    if (o.empty()) return *this;
    return {glm::min(lo, o.lo), glm::max(hi, o.hi)};
  }
  VoxelBox intersect(const VoxelBox& o) const {
    VoxelBox r{glm::max(lo, o.lo), glm::min(hi, o.hi)};
    return r.empty() ? VoxelBox{} : r;
  }
  VoxelBox grow(int n) const { return empty() ? *this : VoxelBox{lo - n, hi + n}; }
  bool operator==(const VoxelBox& o) const {
    return (empty() && o.empty()) || (lo == o.lo && hi == o.hi);
  }
};

}  // namespace cb
