#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace cb {

// A per-brick table (x fastest, then y, then z) of a grid of `from_dims` bricks, re-indexed
// for the grid of `to_dims` bricks it has grown into at `brick_offset`: entry b moves to
// b + brick_offset and every new entry is `empty`. What a growth of the sky does to each table
// keyed by brick (the volume's bricks, the light's bricks, the brick pool's slots and hashes);
// the caller has checked that the old grid fits at the offset.
template <typename T>
std::vector<T> shiftedBrickTable(const std::vector<T>& table, glm::ivec3 from_dims,
                                 glm::ivec3 to_dims, glm::ivec3 brick_offset, T empty = T{}) {
  std::vector<T> shifted(size_t(to_dims.x) * size_t(to_dims.y) * size_t(to_dims.z), empty);
  size_t i = 0;
  for (int z = 0; z < from_dims.z; ++z)
    for (int y = 0; y < from_dims.y; ++y) {
      const glm::ivec3 b = glm::ivec3(0, y, z) + brick_offset;
      const size_t j =
          (size_t(b.z) * size_t(to_dims.y) + size_t(b.y)) * size_t(to_dims.x) + size_t(b.x);
      for (int x = 0; x < from_dims.x; ++x, ++i) shifted[j + size_t(x)] = table[i];
    }
  return shifted;
}

}  // namespace cb
