#include "app/mapping/billows.h"

#include <algorithm>

#include "app/mapping/simplex_noise.h"
#include "app/mapping/stroke_random.h"

namespace cb {

void billowSpheres(const std::vector<Circle>& circles, uint32_t stroke_index,
                   const SphereMappingConfig& config, std::vector<MappedSphere>* spheres) {
  if (config.billow_amplitude <= 0.0f || circles.empty()) return;
  std::vector<float> radii;
  for (const Circle& c : circles) radii.push_back(float(c.radius));
  std::nth_element(radii.begin(), radii.begin() + long(radii.size() / 2), radii.end());
  const float feature = std::max(1.0f, config.billow_feature_radii * radii[radii.size() / 2]);
  const SimplexNoise3 noise(0xB111035u ^ (stroke_index * 0x9E3779B9u));
  for (size_t i = 0; i < circles.size() && i < spheres->size(); ++i) {
    const glm::vec2 p = circles[i].centre / feature;
    // The noise peaks near ±0.7; ×1.4 spreads it over about [-1, 1] before the clamp; u in
    // [0, 1]. Spheres only swell: a sphere smaller than its circle would leave the circle's
    // pixels, which the edge mapping skips as covered, without cloud (a gap in the stroke).
    const float u = 0.5f + 0.5f * std::clamp(1.4f * noise(glm::vec3(p, 0.5f)), -1.0f, 1.0f);
    // Squared: most spheres stay near their circle and the lobes stand out from them.
    (*spheres)[i].radius *= 1.0f + config.billow_amplitude * u * u;
  }
}

std::vector<MappedSphere> edgePuffs(const std::vector<MappedSphere>& spheres, uint32_t stroke_index,
                                    const SphereMappingConfig& config) {
  std::vector<MappedSphere> puffs;
  if (config.puff_probability <= 0.0f || spheres.empty()) return puffs;
  // A stroke of few spheres (a dot, a dab) still gets several chances: kMinTrials in all.
  constexpr size_t kMinTrials = 8;
  const size_t trials = std::max<size_t>(1, (kMinTrials + spheres.size() - 1) / spheres.size());
  for (size_t t = 0; t < spheres.size() * trials; ++t) {
    const size_t i = t / trials;
    StrokeRandom rng(stroke_index, 0x50FF0000ull + t);
    if (rng.uniform() >= config.puff_probability || spheres[i].radius <= 0.0f) continue;
    const float azimuth = float(rng.uniform() * 6.283185307);
    const float elevation = float(rng.uniform() * 0.6981317);  // up to 40°
    const glm::vec3 dir(std::cos(azimuth) * std::cos(elevation), std::sin(elevation),
                        std::sin(azimuth) * std::cos(elevation));
    MappedSphere puff = spheres[i];
    puff.centre += dir * spheres[i].radius;
    puff.radius = spheres[i].radius * float(0.35 + 0.25 * rng.uniform());
    puffs.push_back(puff);
  }
  return puffs;
}

}  // namespace cb
