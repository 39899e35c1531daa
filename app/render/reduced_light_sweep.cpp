#include "app/render/reduced_light_sweep.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "app/core/parallel_for.h"

namespace cb {

VoxelBox ReducedLightSweep::sweep(LightVolume& lv, const Volume& volume, const Light& light,
                                  int divisor) {
  if (divisor <= 1) {
    lv = LightVolume{};
    return sweepLightVolume(lv, volume, light, volume.bounds());
  }
  const glm::ivec3 dims = volume.dims();
  const glm::ivec3 cdims = (dims + divisor - 1) / divisor;
  if (coarse_.dims() != cdims || coarse_.worldMin() != volume.worldMin() ||
      coarse_.worldMax() != volume.worldMax())
    coarse_ = Volume(cdims, volume.worldMin(), volume.worldMax());

  // Block averages of the density (a block at the far edge may be partly outside), each block
  // summed in z, y, x order from the fine rows.
  std::vector<float> coarse(coarse_.voxelCount());
  parallelFor(size_t(cdims.z), 1, [&](size_t, size_t z0, size_t z1) {
    std::vector<float> row(size_t(dims.x));
    std::vector<float> sums(size_t(cdims.x));
    for (int cz = int(z0); cz < int(z1); ++cz)
      for (int cy = 0; cy < cdims.y; ++cy) {
        const glm::ivec3 lo(0, cy * divisor, cz * divisor);
        const glm::ivec3 hi = glm::min(lo + divisor, dims);
        std::fill(sums.begin(), sums.end(), 0.0f);
        for (int z = lo.z; z < hi.z; ++z)
          for (int y = lo.y; y < hi.y; ++y) {
            volume.readLine({0, y, z}, 0, dims.x, row.data());
            for (int cx = 0; cx < cdims.x; ++cx)
              for (int x = cx * divisor; x < std::min((cx + 1) * divisor, dims.x); ++x)
                sums[size_t(cx)] += row[size_t(x)];
          }
        for (int cx = 0; cx < cdims.x; ++cx) {
          const int nx = std::min((cx + 1) * divisor, dims.x) - cx * divisor;
          coarse[coarse_.index(cx, cy, cz)] =
              sums[size_t(cx)] / float(nx * (hi.y - lo.y) * (hi.z - lo.z));
        }
      }
  });
  coarse_.assignDense(coarse.data());

  Light coarse_light = light;
  coarse_light.extinction =
      1.0f - std::pow(1.0f - std::min(light.extinction, 1.0f), float(divisor));
  sweepLightVolume(coarse_light_, coarse_, coarse_light, coarse_.bounds());

  // Trilinear interpolation of the coarse transmittance at every voxel centre, row by row: the
  // four coarse rows around a fine row are blended in y and z once, then each voxel in x.
  lv.dims = dims;
  lv.direction = lightDirectionInVoxels(volume, light);
  lv.extinction = -1.0f;  // matches no light: the next full sweep recomputes everything
  lv.transmittance.resize(volume.voxelCount());
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
  const float* T = coarse_light_.transmittance.data();
  const size_t crow = size_t(cdims.x), cslice = crow * size_t(cdims.y);
  float* out = lv.transmittance.data();
  parallelFor(size_t(dims.z), 1, [&](size_t, size_t z0, size_t z1) {
    std::vector<float> blended(crow);
    for (int z = int(z0); z < int(z1); ++z) {
      const Tap& a = tz[size_t(z)];
      for (int y = 0; y < dims.y; ++y) {
        const Tap& b = ty[size_t(y)];
        const float* r00 = T + size_t(a.i0) * cslice + size_t(b.i0) * crow;
        const float* r01 = T + size_t(a.i0) * cslice + size_t(b.i1) * crow;
        const float* r10 = T + size_t(a.i1) * cslice + size_t(b.i0) * crow;
        const float* r11 = T + size_t(a.i1) * cslice + size_t(b.i1) * crow;
        for (size_t x = 0; x < crow; ++x)
          blended[x] = (r00[x] * (1 - b.t) + r01[x] * b.t) * (1 - a.t) +
                       (r10[x] * (1 - b.t) + r11[x] * b.t) * a.t;
        float* row = out + volume.index(0, y, z);
        for (int x = 0; x < dims.x; ++x) {
          const Tap& c = tx[size_t(x)];
          row[x] = blended[size_t(c.i0)] * (1 - c.t) + blended[size_t(c.i1)] * c.t;
        }
      }
    }
  });
  return volume.bounds();
}

}  // namespace cb
