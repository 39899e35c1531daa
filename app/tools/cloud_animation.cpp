#include "app/tools/cloud_animation.h"

#include <optional>

#include "app/core/parallel_for.h"
#include "app/tools/cloud_morph.h"
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
  // A brick of the half volume averages 2×2×2 bricks of the volume: computed only when one of
  // them is allocated (the rest reads as zeros and stays unallocated).
  const glm::ivec3 bricks = half.brickDims();
  parallelFor(size_t(bricks.z), 1, [&](size_t, size_t bz_begin, size_t bz_end) {
    for (int bz = int(bz_begin); bz < int(bz_end); ++bz)
      for (int by = 0; by < bricks.y; ++by)
        for (int bx = 0; bx < bricks.x; ++bx) {
          bool any = false;
          for (int k = 0; k < 8 && !any; ++k) {
            const glm::ivec3 source(2 * bx + (k & 1), 2 * by + ((k >> 1) & 1), 2 * bz + (k >> 2));
            any = glm::all(glm::lessThan(source, volume.brickDims())) && volume.brick(source);
          }
          if (!any) continue;
          const VoxelBox box = half.brickBox({bx, by, bz});
          for (int z = box.lo.z; z < box.hi.z; ++z)
            for (int y = box.lo.y; y < box.hi.y; ++y)
              for (int x = box.lo.x; x < box.hi.x; ++x) {
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
        }
  });
  half.markDirty(half.bounds());
  return half;
}

Volume withFrame(const Volume& cloud, const WindowFrame& frame) {
  Volume out = cloud;
  pasteVolume(frame.volume, frame.volume.bounds(), frame.at, &out);
  return out;
}

int WindRun::steps() const {
  int n = 0;
  for (const WindSegment& s : segments) n += s.steps;
  return n;
}

WindAnimation::WindAnimation(const Volume& like, float speed, float gust)
    : solver_(like.worldMin(), like.worldMax()),
      centre_(0.5f * (like.worldMin() + like.worldMax())),
      gust_radius_(0.0f) {
  run_.speed = speed;
  run_.gust = gust;
}

namespace {
WindParams windowParams(const ToolWindow& window) {
  WindParams params;
  params.grid = window.wind_cells;
  return params;
}
}  // namespace

WindAnimation::WindAnimation(const ToolWindow& window, float speed, float gust)
    : solver_(window.world_min, window.world_max, windowParams(window)),
      centre_(0.5f * (window.world_min + window.world_max)),
      gust_radius_(window.gust_radius) {
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
  // An updraft in the middle of the sky box (of the window), so the breeze curls the cloud
  // rather than only carrying it (Eq. 3.5 for 0.1 s); a quarter of the home box across.
  const glm::vec3 size = solver_.cellSize() * glm::vec3(solver_.grid());
  const float radius = gust_radius_ > 0.0f ? gust_radius_ : 0.25f * size.x;
  solver_.addForce({0.0f, run_.gust, 0.0f}, centre_, radius, 0.1f);
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

WindowFrame windFrame(const WindRun& run, const Volume& density) {
  const ToolWindow window = toolWindow(density);
  std::optional<Volume> cropped;
  if (!window.whole) cropped = cropToWindow(density, window);
  const Volume& start = cropped ? *cropped : density;
  WindAnimation wind(window, run.speed, run.gust);
  for (const WindSegment& s : run.segments) {
    wind.setDirection(s.dx, s.dz);
    for (int i = 0; i < s.steps; ++i) wind.step();
  }
  WindowFrame frame{start, window.box.lo};
  wind.show(start, &frame.volume, frame.volume.bounds());
  return frame;
}

void blowWind(const WindRun& run, Volume* density) {
  const WindowFrame frame = windFrame(run, *density);
  pasteVolume(frame.volume, frame.volume.bounds(), frame.at, density);
}

WindowFrame morphFrame(const Volume& source, const Volume& target, float t) {
  const ToolWindow window = toolWindow(source, target);
  if (window.whole) return {CloudMorph(source, target).frame(t), glm::ivec3(0)};
  return {CloudMorph(cropToWindow(source, window), cropToWindow(target, window)).frame(t),
          window.box.lo};
}

void blowWindStepByStep(const WindRun& run, Volume* density) {
  WindAnimation wind(*density, run.speed, run.gust);
  for (const WindSegment& s : run.segments) {
    wind.setDirection(s.dx, s.dz);
    for (int i = 0; i < s.steps; ++i) wind.stepDensityItself(density);
  }
}

}  // namespace cb
