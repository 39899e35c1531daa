#include "app/render/reduced_light_sweep.h"

#include <algorithm>
#include <cmath>

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

  // Block averages of the density (a block at the far edge may be partly outside).
  const float* fine = volume.data();
  float* coarse = coarse_.data();
  parallelFor(size_t(cdims.z), 1, [&](size_t, size_t z0, size_t z1) {
    for (int cz = int(z0); cz < int(z1); ++cz)
      for (int cy = 0; cy < cdims.y; ++cy)
        for (int cx = 0; cx < cdims.x; ++cx) {
          const glm::ivec3 lo = glm::ivec3(cx, cy, cz) * divisor;
          const glm::ivec3 hi = glm::min(lo + divisor, dims);
          float sum = 0.0f;
          for (int z = lo.z; z < hi.z; ++z)
            for (int y = lo.y; y < hi.y; ++y) {
              const float* row = fine + volume.index(0, y, z);
              for (int x = lo.x; x < hi.x; ++x) sum += row[x];
            }
          const glm::ivec3 n = hi - lo;
          coarse[coarse_.index(cx, cy, cz)] = sum / float(n.x * n.y * n.z);
        }
  });

  Light coarse_light = light;
  coarse_light.extinction =
      1.0f - std::pow(1.0f - std::min(light.extinction, 1.0f), float(divisor));
  sweepLightVolume(coarse_light_, coarse_, coarse_light, coarse_.bounds());

  // Trilinear interpolation of the coarse transmittance at every voxel centre.
  lv.dims = dims;
  lv.direction = lightDirectionInVoxels(volume, light);
  lv.extinction = -1.0f;  // matches no light: the next full sweep recomputes everything
  lv.transmittance.resize(volume.voxelCount());
  const float inv = 1.0f / float(divisor);
  const auto axis = [&](int i, int n, int* i0, int* i1, float* t) {
    const float c = std::clamp((float(i) + 0.5f) * inv - 0.5f, 0.0f, float(n - 1));
    *i0 = int(c);
    *i1 = std::min(*i0 + 1, n - 1);
    *t = c - float(*i0);
  };
  const float* T = coarse_light_.transmittance.data();
  const auto at = [&](int x, int y, int z) {
    return T[(size_t(z) * size_t(cdims.y) + size_t(y)) * size_t(cdims.x) + size_t(x)];
  };
  float* out = lv.transmittance.data();
  parallelFor(size_t(dims.z), 1, [&](size_t, size_t z0, size_t z1) {
    for (int z = int(z0); z < int(z1); ++z) {
      int z_0, z_1;
      float tz;
      axis(z, cdims.z, &z_0, &z_1, &tz);
      for (int y = 0; y < dims.y; ++y) {
        int y_0, y_1;
        float ty;
        axis(y, cdims.y, &y_0, &y_1, &ty);
        float* row = out + volume.index(0, y, z);
        for (int x = 0; x < dims.x; ++x) {
          int x_0, x_1;
          float tx;
          axis(x, cdims.x, &x_0, &x_1, &tx);
          const float c00 = at(x_0, y_0, z_0) * (1 - tx) + at(x_1, y_0, z_0) * tx;
          const float c10 = at(x_0, y_1, z_0) * (1 - tx) + at(x_1, y_1, z_0) * tx;
          const float c01 = at(x_0, y_0, z_1) * (1 - tx) + at(x_1, y_0, z_1) * tx;
          const float c11 = at(x_0, y_1, z_1) * (1 - tx) + at(x_1, y_1, z_1) * tx;
          row[x] = (c00 * (1 - ty) + c10 * ty) * (1 - tz) + (c01 * (1 - ty) + c11 * ty) * tz;
        }
      }
    }
  });
  return volume.bounds();
}

}  // namespace cb
