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

}  // namespace

VoxelBox ReducedLightSweep::sweep(LightVolume& lv, const Volume& volume, const Light& light,
                                  int divisor) {
  if (divisor <= 1) {
    lv = LightVolume{};
    return sweepLightVolume(lv, volume, light, volume.bounds());
  }
  const glm::ivec3 dims = volume.dims();
  const glm::ivec3 cdims = (dims + divisor - 1) / divisor;
  coarse_ = Volume(cdims, volume.worldMin(), volume.worldMax());  // empty

  averageBlocks(volume, divisor, &coarse_);

  Light coarse_light = light;
  coarse_light.extinction =
      1.0f - std::pow(1.0f - std::min(light.extinction, 1.0f), float(divisor));
  sweepLightVolume(coarse_light_, coarse_, coarse_light, coarse_.bounds());

  // Trilinear interpolation of the coarse transmittance at every voxel centre of the light
  // bricks (the only ones the renderer reads), row by row: the four coarse rows around a fine
  // row are blended in y and z once, then each voxel in x.
  lv.dims = dims;
  lv.direction = lightDirectionInVoxels(volume, light);
  lv.extinction = -1.0f;  // matches no light: the next full sweep recomputes everything
  lv.byte_hash.clear();   // nor are its bricks' bytes known
  lv.lit.recycle(volume.brickDims());  // the previous drag frame's bricks are reused
  lv.through.reset(volume.brickDims());
  struct Tap {
    int i0, i1;
    float t;
  };
  const auto taps = [&](int n_fine, int n_coarse) {
    std::vector<Tap> out(static_cast<size_t>(n_fine));
    for (int i = 0; i < n_fine; ++i) {
      const float c =
          std::clamp((float(i) + 0.5f) / float(divisor) - 0.5f, 0.0f, float(n_coarse - 1));
      const int i0 = int(c);
      out[size_t(i)] = {i0, std::min(i0 + 1, n_coarse - 1), c - float(i0)};
    }
    return out;
  };
  const std::vector<Tap> tx = taps(dims.x, cdims.x), ty = taps(dims.y, cdims.y),
                         tz = taps(dims.z, cdims.z);
  const LightVolume& T = coarse_light_;
  const std::vector<glm::ivec3> bricks = lightBrickList(volume);
  std::vector<float*> out(bricks.size());
  for (size_t k = 0; k < bricks.size(); ++k) out[k] = lv.lit.create(lv.lit.brickIndex(bricks[k]));
  parallelFor(bricks.size(), 4, [&](size_t, size_t k0, size_t k1) {
    std::vector<float> coarse_block, blended;
    for (size_t k = k0; k < k1; ++k) {
      const VoxelBox box = volume.brickBox(bricks[k]);
      // The coarse values this brick interpolates, read once: [c0, c1] per axis.
      const glm::ivec3 c0(tx[size_t(box.lo.x)].i0, ty[size_t(box.lo.y)].i0,
                          tz[size_t(box.lo.z)].i0);
      const glm::ivec3 c1(tx[size_t(box.hi.x - 1)].i1, ty[size_t(box.hi.y - 1)].i1,
                          tz[size_t(box.hi.z - 1)].i1);
      const glm::ivec3 n = c1 - c0 + 1;
      coarse_block.resize(size_t(n.x) * size_t(n.y) * size_t(n.z));
      for (int z = 0; z < n.z; ++z)
        for (int y = 0; y < n.y; ++y)
          for (int x = 0; x < n.x; ++x)
            coarse_block[(size_t(z) * size_t(n.y) + size_t(y)) * size_t(n.x) + size_t(x)] =
                T.at(c0.x + x, c0.y + y, c0.z + z);
      auto coarseRow = [&](int y, int z) {
        return coarse_block.data() +
               (size_t(z - c0.z) * size_t(n.y) + size_t(y - c0.y)) * size_t(n.x);
      };
      blended.resize(size_t(n.x));
      for (int z = box.lo.z; z < box.hi.z; ++z) {
        const Tap& a = tz[size_t(z)];
        for (int y = box.lo.y; y < box.hi.y; ++y) {
          const Tap& b = ty[size_t(y)];
          const float *r00 = coarseRow(b.i0, a.i0), *r01 = coarseRow(b.i1, a.i0),
                      *r10 = coarseRow(b.i0, a.i1), *r11 = coarseRow(b.i1, a.i1);
          for (int x = 0; x < n.x; ++x)
            blended[size_t(x)] = (r00[x] * (1 - b.t) + r01[x] * b.t) * (1 - a.t) +
                                 (r10[x] * (1 - b.t) + r11[x] * b.t) * a.t;
          constexpr int m = Volume::kBrickSize - 1;
          float* row =
              out[k] + ((size_t(z & m) * Volume::kBrickSize + size_t(y & m)) * Volume::kBrickSize);
          for (int x = box.lo.x; x < box.hi.x; ++x) {
            const Tap& c = tx[size_t(x)];
            row[x & m] =
                blended[size_t(c.i0 - c0.x)] * (1 - c.t) + blended[size_t(c.i1 - c0.x)] * c.t;
          }
        }
      }
    }
  });
  lv.lit.dropSpare();
  return volume.bounds();
}

}  // namespace cb
