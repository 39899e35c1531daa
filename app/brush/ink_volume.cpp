#include "app/brush/ink_volume.h"

#include <algorithm>
#include <cmath>
#include <mutex>

#include "app/brush/hash_noise.h"
#include "app/core/parallel_for.h"

namespace cb {
namespace {
inline float smoothstep(float e0, float e1, float x) {
  float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}
}  // namespace

InkVolume::InkVolume(int n, uint32_t seed, const InkVolumeShape& shape)
    : n_(n), shape_(shape), d_(size_t(n) * n * n, 0.0f) {
  const glm::vec3 c = shape.sphere_centre;
  const float R = shape.sphere_radius;
  // Each z slice is written by exactly one chunk: the grid is the same on any thread count.
  parallelFor(size_t(n), 1, [&](size_t, size_t z0, size_t z1) {
    for (size_t z = z0; z < z1; ++z)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          glm::vec3 p = (glm::vec3(x, y, float(z)) + 0.5f) / float(n) * 2.0f - 1.0f;
          // Sphere: solid core, fading over its outer 45 %.
          float sphere = smoothstep(R, 0.55f * R, glm::length(p - c));
          float density = 0.0f;
          if (sphere > 0.0f)
            density = sphere * (0.85f + 0.15f * fractalNoise3D(p.x * 6, p.y * 6, p.z * 6, 2, seed));
          // Plume above the sphere's centre: radius shrinks and the noise thins with height.
          float t = (p.y - c.y) / (1.0f - c.y);
          if (t > 0.0f) {
            float radius = R * (1.0f - 0.55f * t);
            float radial = smoothstep(radius, 0.4f * radius, std::hypot(p.x, p.z));
            if (radial > 0.0f) {
              float noise = fractalNoise3D(p.x * 5, p.y * 5, p.z * 5, 4, seed + 17u);
              float threshold = 0.42f + 0.12f * t;
              float plume = std::clamp((noise - threshold) * 5.0f, 0.0f, 1.0f) * radial;
              density = std::max(density, plume);
            }
          }
          d_[(z * n + y) * n + x] = density;
        }
  });
  const int m = n + 2;
  padded_.assign(size_t(m) * m * m, 0.0f);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        padded_[(size_t(z + 1) * m + (y + 1)) * m + (x + 1)] = voxel(x, y, z);
}

float InkVolume::sample(glm::vec3 p) const {
  // Padded grid: index i of the padded grid is voxel i − 1, with a zero border, so the eight
  // corners never need a bounds check once the cell is inside.
  const int m = n_ + 2;
  glm::vec3 g = (p + 1.0f) * 0.5f * float(n_) + 0.5f;
  glm::vec3 f = glm::floor(g);
  int x0 = int(f.x), y0 = int(f.y), z0 = int(f.z);
  if (x0 < 0 || y0 < 0 || z0 < 0 || x0 >= m - 1 || y0 >= m - 1 || z0 >= m - 1) return 0.0f;
  glm::vec3 t = g - f;
  const float* c = &padded_[(size_t(z0) * m + y0) * m + x0];
  const size_t dy = size_t(m), dz = size_t(m) * m;
  auto lerp = [](float a, float b, float s) { return a + (b - a) * s; };
  float a = lerp(lerp(c[0], c[1], t.x), lerp(c[dy], c[dy + 1], t.x), t.y);
  float b = lerp(lerp(c[dz], c[dz + 1], t.x), lerp(c[dz + dy], c[dz + dy + 1], t.x), t.y);
  return lerp(a, b, t.z);
}

float InkVolume::planeHeight(float pressure) const {
  float p = std::clamp(pressure, 0.0f, 1.0f);
  return shape_.top_y + (shape_.sphere_centre.y - shape_.top_y) * p;
}

std::shared_ptr<const InkVolume> sharedInkVolume(int n, uint32_t seed) {
  struct Entry {
    int n;
    uint32_t seed;
    std::shared_ptr<const InkVolume> ink;
  };
  static std::mutex mutex;
  static std::vector<Entry> made;  // one per distinct (n, seed): a process sees one or two
  std::lock_guard<std::mutex> lock(mutex);
  for (const Entry& e : made)
    if (e.n == n && e.seed == seed) return e.ink;
  made.push_back({n, seed, std::make_shared<const InkVolume>(n, seed)});
  return made.back().ink;
}

}  // namespace cb
