#include "app/tools/tool_window.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <vector>

#include "app/core/parallel_for.h"
#include "app/tools/wind.h"
#include "app/volume/sky_extent.h"

namespace cb {
namespace {

constexpr int kBrick = Volume::kBrickSize;

int floorTo(int v, int step) {
  return (v >= 0 ? v : v - step + 1) / step * step;
}
int ceilTo(int v, int step) {
  return floorTo(v + step - 1, step);
}

// One axis (x or z) of a wide sky's window: `lo`, `hi` the content, `size` the sky's voxels,
// `grid` the home box's, `home` its first voxel (see the header comment for the rule).
void windowAxis(int lo, int hi, int size, int grid, int home, int* out_lo, int* out_hi) {
  const int margin = std::max(kBrick, ceilTo(grid / 8, kBrick));
  const int p0 = std::max(0, lo - margin), p1 = std::min(size, hi + margin);
  // a. A home-box tile holding it: the tile aligned with the home box where it starts, else the
  // tile flush with either edge of the sky.
  const int k = (p0 - home >= 0 ? p0 - home : p0 - home - grid + 1) / grid;
  for (const int tile : {home + k * grid, 0, size - grid})
    if (tile >= 0 && tile + grid <= size && tile <= p0 && p1 <= tile + grid) {
      *out_lo = tile;
      *out_hi = tile + grid;
      return;
    }
  // b. A home box across, centred on it.
  if (p1 - p0 <= grid) {
    int s = floorTo((p0 + p1 - grid) / 2, kBrick);
    s = std::min(s, p0);
    if (s + grid < p1) s = p1 - grid;
    s = std::clamp(s, 0, size - grid);
    *out_lo = s;
    *out_hi = s + grid;
    return;
  }
  // c. Itself, snapped out to bricks.
  *out_lo = std::max(0, floorTo(p0, kBrick));
  *out_hi = std::min(size, ceilTo(p1, kBrick));
}

ToolWindow wholeWindow(const Volume& volume) {
  ToolWindow w;
  w.box = volume.bounds();
  windowWorldBox(volume, w.box, &w.world_min, &w.world_max);
  w.wind_cells = WindParams{}.grid;
  w.gust_radius = 0.0f;
  w.whole = true;
  return w;
}

}  // namespace

VoxelBox densityBricks(const Volume& volume) {
  const std::vector<glm::ivec3> bricks = volume.allocatedBrickList();
  std::vector<uint8_t> holds(bricks.size(), 0);
  parallelFor(bricks.size(), 64, [&](size_t, size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      const float* v = volume.brick(bricks[i]);
      holds[i] = std::any_of(v, v + Volume::kBrickVoxels, [](float d) { return d != 0.0f; });
    }
  });
  VoxelBox box;
  for (size_t i = 0; i < bricks.size(); ++i)
    if (holds[i]) box = box.unite(volume.brickBox(bricks[i]));
  return box;
}

ToolWindow toolWindow(const Volume& volume, const VoxelBox& content) {
  const std::optional<SkyExtent> sky = skyExtentOf(volume);
  if (!sky || sky->span == 1 || content.empty()) return wholeWindow(volume);
  const glm::ivec3 d = volume.dims();
  const glm::ivec3 home = sky->homeOffset();
  ToolWindow w;
  w.whole = false;
  w.box.lo.y = 0;
  w.box.hi.y = d.y;
  windowAxis(content.lo.x, content.hi.x, d.x, sky->grid, home.x, &w.box.lo.x, &w.box.hi.x);
  windowAxis(content.lo.z, content.hi.z, d.z, sky->grid, home.z, &w.box.lo.z, &w.box.hi.z);
  windowWorldBox(volume, w.box, &w.world_min, &w.world_max);
  // 64 cells per home box along each axis, as over the one-box sky.
  const int per_home = WindParams{}.grid.x;
  const glm::ivec3 size = w.dims();
  for (int a = 0; a < 3; ++a)
    w.wind_cells[a] = std::max(1, int(std::lround(double(per_home) * size[a] / sky->grid)));
  // A quarter of the home box's width, as a quarter of the one-box sky's.
  w.gust_radius = 0.25f * float(sky->grid) * volume.voxelSize().x;
  return w;
}

ToolWindow toolWindow(const Volume& volume) {
  const std::optional<SkyExtent> sky = skyExtentOf(volume);
  if (!sky || sky->span == 1) return wholeWindow(volume);  // no need to look at the bricks
  return toolWindow(volume, densityBricks(volume));
}

ToolWindow toolWindow(const Volume& source, const Volume& target) {
  const std::optional<SkyExtent> sky = skyExtentOf(source);
  if (!sky || sky->span == 1) return wholeWindow(source);
  return toolWindow(source, densityBricks(source).unite(densityBricks(target)));
}

void windowWorldBox(const Volume& volume, const VoxelBox& box, glm::vec3* world_min,
                    glm::vec3* world_max) {
  const bool whole = box == volume.bounds();
  *world_min = whole ? volume.worldMin() : volume.voxelToWorld(glm::vec3(box.lo));
  *world_max = whole ? volume.worldMax() : volume.voxelToWorld(glm::vec3(box.hi));
}

Volume cropToWindow(const Volume& volume, const VoxelBox& box, glm::vec3 world_min,
                    glm::vec3 world_max) {
  const VoxelBox inside = box.intersect(volume.bounds());
  Volume out(box.hi - box.lo, world_min, world_max);
  if (inside.empty()) return out;
  // Only allocated bricks hold anything: copy their rows inside the box.
  const glm::ivec3 b_lo = inside.lo >> Volume::kBrickShift;
  const glm::ivec3 b_hi = ((inside.hi - 1) >> Volume::kBrickShift) + 1;
  parallelFor(size_t(b_hi.z - b_lo.z), 1, [&](size_t, size_t zb, size_t ze) {
    for (int bz = b_lo.z + int(zb); bz < b_lo.z + int(ze); ++bz)
      for (int by = b_lo.y; by < b_hi.y; ++by)
        for (int bx = b_lo.x; bx < b_hi.x; ++bx) {
          const float* src = volume.brick({bx, by, bz});
          if (!src) continue;
          const VoxelBox part = volume.brickBox({bx, by, bz}).intersect(inside);
          const int n = part.hi.x - part.lo.x;
          for (int z = part.lo.z; z < part.hi.z; ++z)
            for (int y = part.lo.y; y < part.hi.y; ++y) {
              const size_t in_brick =
                  (size_t(z & (kBrick - 1)) * kBrick + size_t(y & (kBrick - 1))) * kBrick +
                  size_t(part.lo.x & (kBrick - 1));
              out.writeLine(glm::ivec3(part.lo.x, y, z) - box.lo, 0, n, src + in_brick);
            }
        }
  });
  out.markDirty(out.bounds());
  return out;
}

Volume cropToWindow(const Volume& volume, const ToolWindow& window) {
  return cropToWindow(volume, window.box, window.world_min, window.world_max);
}

VoxelBox halfBox(const VoxelBox& box) {
  return {box.lo / 2, (box.hi + 1) / 2};
}

}  // namespace cb
