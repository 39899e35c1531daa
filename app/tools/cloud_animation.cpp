#include "app/tools/cloud_animation.h"

#include "app/core/parallel_for.h"
#include "app/tools/tool_error.h"
#include "app/volume/scene_generators.h"
#include "app/volume/sky_extent.h"
#include "app/volume/volume_file.h"

namespace cb {

Volume loadMorphTarget(const std::string& source, const Volume& like) {
  Volume target;
  if (source.rfind("bundled:", 0) == 0) {
    const std::string digits = source.substr(8);
    char* end = nullptr;
    const unsigned long seed = std::strtoul(digits.c_str(), &end, 10);
    if (digits.empty() || *end != '\0' || seed > 0xffffffffUL)
      throw ToolError(ToolErrorKind::kMismatchedVolumes,
                      "morph target '" + source + "': expected bundled:SEED (a number)");
    // The bundled cloud of the sky's home box, in the home box.
    const std::optional<SkyExtent> sky = skyExtentOf(like);
    target = sky ? placeInSky(makeBundledCumulus(glm::ivec3(sky->grid), uint32_t(seed)), *sky)
                 : makeBundledCumulus(like.dims(), uint32_t(seed));
  } else {
    target = loadVolume(source);
    // A cloud saved from the one-box sky morphs into the home box of a wider one.
    const std::optional<SkyExtent> sky = skyExtentOf(like);
    if (sky && sky->span > 1 && isHomeBoxCloud(target, *sky)) target = placeInSky(target, *sky);
  }
  if (target.dims() != like.dims() || target.worldMin() != like.worldMin() ||
      target.worldMax() != like.worldMax())
    throw ToolError(ToolErrorKind::kMismatchedVolumes,
                    "morph target " + source + ": a " + std::to_string(target.dims().x) + "x" +
                        std::to_string(target.dims().y) + "x" + std::to_string(target.dims().z) +
                        " cloud does not fit this " + std::to_string(like.dims().x) + "x" +
                        std::to_string(like.dims().y) + "x" + std::to_string(like.dims().z) +
                        " sky");
  return target;
}

Volume halfResolution(const Volume& volume) {
  const glm::ivec3 d = volume.dims();
  const glm::ivec3 h = (d + 1) / 2;
  Volume half(h, volume.worldMin(), volume.worldMax());
  parallelFor(size_t(h.z), 4, [&](size_t, size_t z_begin, size_t z_end) {
    for (int z = int(z_begin); z < int(z_end); ++z)
      for (int y = 0; y < h.y; ++y)
        for (int x = 0; x < h.x; ++x) {
          float sum = 0.0f;
          int n = 0;
          for (int k = 0; k < 2; ++k)
            for (int j = 0; j < 2; ++j)
              for (int i = 0; i < 2; ++i) {
                const glm::ivec3 p(2 * x + i, 2 * y + j, 2 * z + k);
                if (p.x >= d.x || p.y >= d.y || p.z >= d.z) continue;
                sum += volume.at(p.x, p.y, p.z);
                ++n;
              }
          if (sum != 0.0f) half.voxelForWrite(x, y, z) = sum / float(n);
        }
  });
  half.markDirty(half.bounds());
  return half;
}

int WindRun::steps() const {
  int n = 0;
  for (const WindSegment& s : segments) n += s.steps;
  return n;
}

WindAnimation::WindAnimation(const Volume& like, float speed, float gust)
    : solver_(like.worldMin(), like.worldMax()),
      centre_(0.5f * (like.worldMin() + like.worldMax())) {
  run_.speed = speed;
  run_.gust = gust;
}

void WindAnimation::setDirection(float dx, float dz) {
  if (!run_.segments.empty() && run_.segments.back().steps == 0) run_.segments.pop_back();
  run_.segments.push_back({dx, dz, 0});
  blow();
}

void WindAnimation::blow() {
  const WindSegment& s = run_.segments.back();
  const glm::vec2 d = glm::length(glm::vec2(s.dx, s.dz)) > 0.0f
                          ? glm::normalize(glm::vec2(s.dx, s.dz))
                          : glm::vec2(0.0f);
  solver_.setUniformWind(run_.speed * glm::vec3(d.x, 0.0f, d.y));
  // An updraft in the middle of the sky box, so the breeze curls the cloud rather than only
  // carrying it (Eq. 3.5 for 0.1 s).
  const glm::vec3 size = solver_.cellSize() * glm::vec3(solver_.grid());
  solver_.addForce({0.0f, run_.gust, 0.0f}, centre_, 0.25f * size.x, 0.1f);
}

void WindAnimation::step() {
  if (run_.segments.empty()) setDirection(1.0f, 0.0f);
  ++run_.segments.back().steps;
  solver_.step(kWindStepSeconds);
}

VoxelBox WindAnimation::show(const Volume& start, Volume* out, const VoxelBox& previous) const {
  return solver_.resampleDensity(start, out, previous);
}

void WindAnimation::stepDensityItself(Volume* density) {
  if (run_.segments.empty()) setDirection(1.0f, 0.0f);
  ++run_.segments.back().steps;
  solver_.stepVelocity(kWindStepSeconds);
  solver_.advectDensityEveryVoxel(kWindStepSeconds, density);
}

void blowWind(const WindRun& run, Volume* density) {
  WindAnimation wind(*density, run.speed, run.gust);
  for (const WindSegment& s : run.segments) {
    wind.setDirection(s.dx, s.dz);
    for (int i = 0; i < s.steps; ++i) wind.step();
  }
  const Volume start = *density;
  wind.show(start, density, density->bounds());
}

void blowWindStepByStep(const WindRun& run, Volume* density) {
  WindAnimation wind(*density, run.speed, run.gust);
  for (const WindSegment& s : run.segments) {
    wind.setDirection(s.dx, s.dz);
    for (int i = 0; i < s.steps; ++i) wind.stepDensityItself(density);
  }
}

}  // namespace cb
