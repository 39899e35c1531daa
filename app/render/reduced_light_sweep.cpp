#include "app/render/reduced_light_sweep.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "app/core/parallel_for.h"

namespace cb {

namespace {

// Block averages of the density (a block at the far edge may be partly outside), each block
// summed in z, y, x order from the fine rows; only the coarse bricks holding a block that
// meets an allocated fine brick (the others average to 0 and stay unallocated).
void averageBlocks(const Volume& volume, int divisor, Volume* coarse) {
  const glm::ivec3 dims = volume.dims();
  std::vector<uint8_t> wanted(coarse->brickCount(), 0);
  const glm::ivec3 cbd = coarse->brickDims();
  for (const glm::ivec3 b : volume.allocatedBrickList()) {
    const VoxelBox box = volume.brickBox(b);
    const glm::ivec3 lo = (box.lo / divisor) >> Volume::kBrickShift,
                     hi = ((box.hi - 1) / divisor) >> Volume::kBrickShift;
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x)
          wanted[(size_t(z) * size_t(cbd.y) + size_t(y)) * size_t(cbd.x) + size_t(x)] = 1;
  }
  std::vector<glm::ivec3> coarse_bricks;
  for (int z = 0; z < cbd.z; ++z)
    for (int y = 0; y < cbd.y; ++y)
      for (int x = 0; x < cbd.x; ++x)
        if (wanted[(size_t(z) * size_t(cbd.y) + size_t(y)) * size_t(cbd.x) + size_t(x)])
          coarse_bricks.push_back({x, y, z});
  parallelFor(coarse_bricks.size(), 1, [&](size_t, size_t k0, size_t k1) {
    std::vector<float> row(size_t(Volume::kBrickSize * divisor));
    std::vector<float> sums(static_cast<size_t>(Volume::kBrickSize));
    for (size_t k = k0; k < k1; ++k) {
      const VoxelBox cbox = coarse->brickBox(coarse_bricks[k]);
      const int x0 = cbox.lo.x * divisor, x1 = std::min(cbox.hi.x * divisor, dims.x);
      for (int cz = cbox.lo.z; cz < cbox.hi.z; ++cz)
        for (int cy = cbox.lo.y; cy < cbox.hi.y; ++cy) {
          const glm::ivec3 lo(x0, cy * divisor, cz * divisor);
          const glm::ivec3 hi = glm::min(glm::ivec3(x1, lo.y + divisor, lo.z + divisor), dims);
          std::fill(sums.begin(), sums.end(), 0.0f);
          for (int z = lo.z; z < hi.z; ++z)
            for (int y = lo.y; y < hi.y; ++y) {
              volume.readLine({x0, y, z}, 0, x1 - x0, row.data());
              for (int cx = cbox.lo.x; cx < cbox.hi.x; ++cx)
                for (int x = cx * divisor; x < std::min((cx + 1) * divisor, dims.x); ++x)
                  sums[size_t(cx - cbox.lo.x)] += row[size_t(x - x0)];
            }
          for (int cx = cbox.lo.x; cx < cbox.hi.x; ++cx) {
            const int nx = std::min((cx + 1) * divisor, dims.x) - cx * divisor;
            const float average =
                sums[size_t(cx - cbox.lo.x)] / float(nx * (hi.y - lo.y) * (hi.z - lo.z));
            if (std::bit_cast<uint32_t>(average) != 0) coarse->voxelForWrite(cx, cy, cz) = average;
          }
        }
    }
  });
  coarse->markDirty(coarse->bounds());
}

// The fine box of the allocated bricks (empty for an empty volume).
VoxelBox allocatedBox(const Volume& volume) {
  VoxelBox box;
  for (const glm::ivec3 b : volume.allocatedBrickList()) box = box.unite(volume.brickBox(b));
  return box;
}

}  // namespace

float LightPreviewGrid::sample(glm::vec3 p) const {
  if (divisor == 0 || bytes.empty()) return 1.0f;
  const glm::vec3 c =
      glm::clamp(p / float(divisor) - 0.5f - glm::vec3(lo), glm::vec3(0.0f), glm::vec3(size - 1));
  const glm::ivec3 i0(c), i1 = glm::min(i0 + 1, size - 1);
  const glm::vec3 t = c - glm::vec3(i0);
  const auto at = [&](int x, int y, int z) {
    return float(bytes[(size_t(z) * size_t(size.y) + size_t(y)) * size_t(size.x) + size_t(x)]) /
           255.0f;
  };
  const auto row = [&](int y, int z) { return at(i0.x, y, z) * (1 - t.x) + at(i1.x, y, z) * t.x; };
  const float z0 = row(i0.y, i0.z) * (1 - t.y) + row(i1.y, i0.z) * t.y;
  const float z1 = row(i0.y, i1.z) * (1 - t.y) + row(i1.y, i1.z) * t.y;
  return z0 * (1 - t.z) + z1 * t.z;
}

const LightPreviewGrid& ReducedLightSweep::sweep(const Volume& volume, const Light& light,
                                                 int divisor) {
  const glm::ivec3 dims = volume.dims();
  const VoxelBox fine = allocatedBox(volume);
  divisor = std::max(divisor, 2);
  glm::ivec3 lo(0), size(1), cdims(1);
  for (;; divisor *= 2) {
    cdims = (dims + divisor - 1) / divisor;
    if (fine.empty()) break;
    lo = glm::max(fine.lo / divisor - 1, glm::ivec3(0));
    size = glm::min((fine.hi + divisor - 1) / divisor + 1, cdims) - lo;
    if (size_t(size.x) * size_t(size.y) * size_t(size.z) <= kMaxGridVoxels) break;
  }
  grid_.divisor = divisor;
  grid_.lo = lo;
  grid_.size = size;
  grid_.bytes.assign(size_t(size.x) * size_t(size.y) * size_t(size.z), 255);
  if (fine.empty()) return grid_;

  if (averaged_id_ != volume.instanceId() || averaged_generation_ != volume.generation() ||
      averaged_divisor_ != divisor) {
    coarse_ = Volume(cdims, volume.worldMin(), volume.worldMax());  // empty
    averageBlocks(volume, divisor, &coarse_);
    coarse_light_ = LightVolume{};
    averaged_id_ = volume.instanceId();
    averaged_generation_ = volume.generation();
    averaged_divisor_ = divisor;
  }
  Light coarse_light = light;
  coarse_light.extinction =
      1.0f - std::pow(1.0f - std::min(light.extinction, 1.0f), float(divisor));
  sweepLightVolume(coarse_light_, coarse_, coarse_light, coarse_.bounds());

  // The box's rows as bytes.
  const size_t rows = size_t(size.y) * size_t(size.z);
  parallelFor(rows, 16, [&](size_t, size_t r0, size_t r1) {
    std::vector<float> row(size_t(size.x));
    for (size_t r = r0; r < r1; ++r) {
      const int y = lo.y + int(r % size_t(size.y)), z = lo.z + int(r / size_t(size.y));
      coarse_light_.readRow({lo.x, y, z}, size.x, row.data());
      uint8_t* out = grid_.bytes.data() + r * size_t(size.x);
      for (int x = 0; x < size.x; ++x) out[x] = unorm8(row[size_t(x)]);
    }
  });
  return grid_;
}

}  // namespace cb
