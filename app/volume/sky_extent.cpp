#include "app/volume/sky_extent.h"

#include "app/volume/volume_paste.h"

#include <algorithm>
#include <cmath>
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

int widestSkySpan(int grid, int span, int max_span) {
  // A span step moves the home box by grid/2 voxels in x and z: whole bricks when grid/2 is.
  if (grid % (2 * Volume::kBrickSize) != 0) return span;
  int widest = span;
  for (int s = span + 1; s <= max_span; ++s)
    if (SkyExtent{grid, s}.check().empty()) widest = s;
  return widest;
}

SkyExtent skyToHold(const SkyExtent& from, int max_span, glm::vec2 xz_min, glm::vec2 xz_max) {
  const int widest = widestSkySpan(from.grid, from.span, max_span);
  // The sky of span s covers [-s, s] in x and z.
  const glm::vec4 ends(-xz_min.x, -xz_min.y, xz_max.x, xz_max.y);
  if (glm::any(glm::isnan(ends))) return {from.grid, widest};  // unknown: as wide as allowed
  const float reach = std::max({ends.x, ends.y, ends.z, ends.w});
  if (!(reach <= float(widest))) return {from.grid, widest};
  const int needed = int(std::ceil(reach));
  return {from.grid, std::clamp(needed, from.span, widest)};
}

SkyExtent skyToHold(const SkyExtent& from, int max_span, const SkyReach& reach) {
  if (!reach.inked) return from;
  if (!reach.bounded) return {from.grid, widestSkySpan(from.grid, from.span, max_span)};
  return skyToHold(from, max_span, reach.xz_min, reach.xz_max);
}

glm::ivec3 growthOffset(const SkyExtent& from, const SkyExtent& to) {
  return to.homeOffset() - from.homeOffset();
}

Volume growSky(Volume&& sky, const SkyExtent& from, const SkyExtent& to) {
  const glm::ivec3 offset = growthOffset(from, to);
  if (to.grid != from.grid || to.span < from.span || !to.check().empty() ||
      sky.dims() != from.dims() || offset % Volume::kBrickSize != glm::ivec3(0))
    throw std::invalid_argument("growSky: a sky of span " + std::to_string(from.span) +
                                " cannot grow by whole bricks to span " + std::to_string(to.span) +
                                " (grid " + std::to_string(from.grid) + ")");
  return std::move(sky).movedInto(to.dims(), to.worldMin(), to.worldMax(),
                                  offset / Volume::kBrickSize);
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
