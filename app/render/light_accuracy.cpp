#include "app/render/light_accuracy.h"

#include <cmath>
#include <cstdint>

namespace cb {

LightAccuracy compareWithReference(const LightVolume& light_volume, const Volume& volume,
                                   const std::vector<float>& reference) {
  std::vector<uint8_t> read(volume.brickCount(), 0);
  const glm::ivec3 bd = volume.brickDims();
  auto brickIndex = [&](glm::ivec3 b) {
    return (size_t(b.z) * size_t(bd.y) + size_t(b.y)) * size_t(bd.x) + size_t(b.x);
  };
  for (const glm::ivec3 b : lightBrickList(volume)) read[brickIndex(b)] = 1;
  LightAccuracy a;
  double sum = 0.0, shadowed_sum = 0.0;
  const glm::ivec3 dims = volume.dims();
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x) {
        const float ref = reference[volume.index(x, y, z)];
        if (ref < 0.0f) continue;  // a slice the reference did not march
        if (!read[brickIndex(glm::ivec3(x, y, z) >> Volume::kBrickShift)]) {
          ++a.unread_voxels;
          continue;
        }
        const double e = std::abs(double(light_volume.at(x, y, z)) - double(ref));
        sum += e;
        ++a.voxels;
        if (ref < 0.999f) {
          shadowed_sum += e;
          ++a.shadowed_voxels;
        }
      }
  a.mae = a.voxels ? sum / double(a.voxels) : 0.0;
  a.shadowed_mae = a.shadowed_voxels ? shadowed_sum / double(a.shadowed_voxels) : 0.0;
  return a;
}

}  // namespace cb
