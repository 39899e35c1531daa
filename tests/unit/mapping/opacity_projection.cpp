#include "opacity_projection.h"

#include <algorithm>
#include <cmath>

#include "app/core/parallel_for.h"

namespace cb::test {

std::vector<float> projectOpacity(const Volume& volume, const Camera& camera, int width, int height,
                                  float k) {
  std::vector<float> out(size_t(width) * height, 0.0f);
  const glm::vec3 lo = volume.worldMin(), hi = volume.worldMax(), vs = volume.voxelSize();
  const float step = std::min({vs.x, vs.y, vs.z});
  const glm::ivec3 dims = volume.dims();
  parallelFor(size_t(height), 8, [&](size_t, size_t y0, size_t y1) {
    for (size_t y = y0; y < y1; ++y)
      for (int x = 0; x < width; ++x) {
        glm::vec3 o, d;
        camera.pixelRay(float(x), float(y), width, height, &o, &d);
        float t0 = 0.0f, t1 = 1e30f;
        bool hit = true;
        for (int a = 0; a < 3 && hit; ++a) {
          if (std::abs(d[a]) < 1e-12f) {
            hit = o[a] >= lo[a] && o[a] <= hi[a];
            continue;
          }
          float ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
          if (ta > tb) std::swap(ta, tb);
          t0 = std::max(t0, ta);
          t1 = std::min(t1, tb);
        }
        if (!hit || t0 >= t1) continue;
        const float exponent = step * 128.0f;
        float transmittance = 1.0f;
        for (float t = t0 + 0.5f * step; t < t1 && transmittance > 1e-4f; t += step) {
          glm::ivec3 v(glm::floor(volume.worldToVoxel(o + d * t)));
          v = glm::clamp(v, glm::ivec3(0), dims - 1);
          const float density = std::min(1.0f, volume.at(v.x, v.y, v.z));
          if (density > 0.0f) transmittance *= std::pow(1.0f - k * density, exponent);
        }
        out[y * width + size_t(x)] = 1.0f - transmittance;
      }
  });
  return out;
}

double anisotropyAlong(const std::vector<float>& img, int w, int h, glm::vec2 u) {
  u = glm::normalize(u);
  const glm::vec2 across(-u.y, u.x);
  double along_energy = 0.0, across_energy = 0.0;
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      glm::vec2 g(0.5f * (img[size_t(y) * w + x + 1] - img[size_t(y) * w + x - 1]),
                  0.5f * (img[size_t(y + 1) * w + x] - img[size_t(y - 1) * w + x]));
      along_energy += double(glm::dot(g, u)) * glm::dot(g, u);
      across_energy += double(glm::dot(g, across)) * glm::dot(g, across);
    }
  return along_energy > 0.0 ? across_energy / along_energy : 0.0;
}

}  // namespace cb::test
