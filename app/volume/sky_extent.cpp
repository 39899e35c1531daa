#include "app/volume/sky_extent.h"

#include "app/volume/volume_paste.h"

#include <stdexcept>

namespace cb {

std::string SkyExtent::check() const {
  if (grid < 1 || span < 1 || span > kMaxSkySpan)
    return "sky span " + std::to_string(span) + " with grid " + std::to_string(grid) +
           ": expected a span of 1.." + std::to_string(kMaxSkySpan);
  if (long(span) * grid > kMaxVolumeDim)
    return "sky span " + std::to_string(span) + " × grid " + std::to_string(grid) + " = " +
           std::to_string(long(span) * grid) + " voxels across, more than " +
           std::to_string(kMaxVolumeDim);
  if ((span - 1) * grid % 2 != 0)
    return "sky span " + std::to_string(span) + " with an odd grid " + std::to_string(grid) +
           " would put the home box between voxels: use an odd span or an even grid";
  return {};
}

std::optional<SkyExtent> skyExtentOf(const Volume& volume) {
  const glm::ivec3 d = volume.dims();
  if (d.y < 1 || d.x != d.z || d.x % d.y != 0) return std::nullopt;
  const SkyExtent sky{d.y, d.x / d.y};
  if (!sky.check().empty() || volume.worldMin() != sky.worldMin() ||
      volume.worldMax() != sky.worldMax())
    return std::nullopt;
  return sky;
}

Volume makeSkyVolume(const SkyExtent& extent) {
  const std::string problem = extent.check();
  if (!problem.empty()) throw std::invalid_argument(problem);
  return Volume(extent.dims(), extent.worldMin(), extent.worldMax());
}

bool isHomeBoxCloud(const Volume& volume, const SkyExtent& extent) {
  return volume.dims() == glm::ivec3(extent.grid) && volume.worldMin() == glm::vec3(-1.0f) &&
         volume.worldMax() == glm::vec3(1.0f);
}

Volume placeInSky(const Volume& home, const SkyExtent& extent) {
  if (home.dims() != glm::ivec3(extent.grid))
    throw std::invalid_argument("placeInSky: the home volume is not " +
                                std::to_string(extent.grid) + "³");
  if (extent.span == 1) return home;
  Volume sky = makeSkyVolume(extent);
  pasteVolume(home, home.bounds(), extent.homeOffset(), &sky);
  return sky;
}

}  // namespace cb
