#include "app/volume/volume_paste.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include "app/core/parallel_for.h"

namespace cb {
namespace {

constexpr int kBrick = Volume::kBrickSize;
// More dirty boxes than this per paste become one box (the volume keeps its last 256 changes).
constexpr size_t kMaxDirtyRuns = 64;

}  // namespace

VoxelBox pasteVolume(const Volume& from, const VoxelBox& region, glm::ivec3 at, Volume* into) {
  // The part of the region that lands inside `into`.
  const VoxelBox src =
      region.intersect(from.bounds()).intersect({into->bounds().lo - at, into->bounds().hi - at});
  if (src.empty()) return {};
  const VoxelBox dst{src.lo + at, src.hi + at};
  // Destination bricks, each z layer of them handled by one task (which alone flags them).
  const glm::ivec3 b_lo = dst.lo >> Volume::kBrickShift;
  const glm::ivec3 b_hi = ((dst.hi - 1) >> Volume::kBrickShift) + 1;
  const glm::ivec3 nb = b_hi - b_lo;
  std::vector<uint8_t> changed(size_t(nb.x) * nb.y * nb.z, 0);
  auto flag = [&](int bx, int by, int bz) -> uint8_t& {
    return changed[(size_t(bz - b_lo.z) * nb.y + size_t(by - b_lo.y)) * nb.x + size_t(bx - b_lo.x)];
  };
  const int n = dst.hi.x - dst.lo.x;
  parallelFor(size_t(nb.z), 1, [&](size_t, size_t zb, size_t ze) {
    std::vector<float> a(static_cast<size_t>(n)), b(static_cast<size_t>(n));
    for (int bz = b_lo.z + int(zb); bz < b_lo.z + int(ze); ++bz) {
      const int z0 = std::max(dst.lo.z, bz * kBrick), z1 = std::min(dst.hi.z, (bz + 1) * kBrick);
      for (int z = z0; z < z1; ++z)
        for (int y = dst.lo.y; y < dst.hi.y; ++y) {
          into->readLine({dst.lo.x, y, z}, 0, n, a.data());
          from.readLine(glm::ivec3(dst.lo.x, y, z) - at, 0, n, b.data());
          if (std::memcmp(a.data(), b.data(), sizeof(float) * size_t(n)) == 0) continue;
          // Each brick's segment of the row, written and flagged when it differs.
          for (int x = dst.lo.x; x < dst.hi.x;) {
            const int end = std::min(dst.hi.x, (x / kBrick + 1) * kBrick);
            const size_t i = size_t(x - dst.lo.x), m = size_t(end - x);
            if (std::memcmp(&a[i], &b[i], sizeof(float) * m) != 0) {
              into->writeLine({x, y, z}, 0, int(m), &b[i]);
              flag(x / kBrick, y / kBrick, bz) = 1;
            }
            x = end;
          }
        }
    }
  });
  // Runs of changed bricks along x, in the fixed brick order.
  std::vector<VoxelBox> runs;
  VoxelBox all;
  for (int bz = b_lo.z; bz < b_hi.z; ++bz)
    for (int by = b_lo.y; by < b_hi.y; ++by)
      for (int bx = b_lo.x; bx < b_hi.x; ++bx) {
        if (!flag(bx, by, bz)) continue;
        int end = bx;
        while (end < b_hi.x && flag(end, by, bz)) ++end;
        const VoxelBox run =
            VoxelBox{glm::ivec3(bx, by, bz) * kBrick, glm::ivec3(end, by + 1, bz + 1) * kBrick}
                .intersect(dst);
        runs.push_back(run);
        all = all.unite(run);
        bx = end;
      }
  if (runs.size() > kMaxDirtyRuns) {
    into->markDirty(all);
  } else {
    for (const VoxelBox& run : runs) into->markDirty(run);
  }
  return all;
}

}  // namespace cb
