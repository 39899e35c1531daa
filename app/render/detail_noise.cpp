#include "app/render/detail_noise.h"

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "app/core/hash32.h"

namespace cb {
namespace {

// One of the 12 edge directions of a cube (Perlin's improved noise gradients).
glm::vec3 gradient(glm::ivec3 cell, int period, uint32_t seed) {
  static const glm::vec3 kDirs[12] = {{1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0},
                                      {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
                                      {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}};
  glm::ivec3 c = ((cell % period) + period) % period;  // wrap: the noise repeats
  uint32_t h = hashU32(uint32_t(c.x) + hashU32(uint32_t(c.y) + hashU32(uint32_t(c.z) + seed)));
  return kDirs[h % 12u];
}

float fade(float t) {
  return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
}

// Perlin gradient noise at p (lattice units) repeating every `period` cells; about [-1, 1].
float perlin(glm::vec3 p, int period, uint32_t seed) {
  glm::ivec3 i = glm::ivec3(glm::floor(p));
  glm::vec3 f = p - glm::floor(p);
  float v[8];
  for (int k = 0; k < 8; ++k) {
    glm::ivec3 o(k & 1, (k >> 1) & 1, (k >> 2) & 1);
    v[k] = glm::dot(gradient(i + o, period, seed), f - glm::vec3(o));
  }
  glm::vec3 w(fade(f.x), fade(f.y), fade(f.z));
  float x0 = glm::mix(v[0], v[1], w.x), x1 = glm::mix(v[2], v[3], w.x);
  float x2 = glm::mix(v[4], v[5], w.x), x3 = glm::mix(v[6], v[7], w.x);
  return glm::mix(glm::mix(x0, x1, w.y), glm::mix(x2, x3, w.y), w.z);
}

}  // namespace

DetailNoise makeDetailNoise(int size, int base_cells, int octaves, uint32_t seed) {
  DetailNoise n;
  n.size = size;
  std::vector<float> v(size_t(size) * size * size);
  for (int z = 0; z < size; ++z)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        glm::vec3 unit = (glm::vec3(x, y, z) + 0.5f) / float(size);
        float sum = 0.0f, weight = 1.0f;
        int cells = base_cells;
        for (int o = 0; o < octaves; ++o) {
          // fbm = Σ wⁱ·perlin(sⁱ·x), w = ½, s = 2 (seed 004).
          sum += weight * perlin(unit * float(cells), cells, seed + uint32_t(o) * 101u);
          weight *= 0.5f;
          cells *= 2;
        }
        v[(size_t(z) * size + y) * size + x] = sum;
      }
  auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  const float range = std::max(*hi - *lo, 1e-6f);
  n.texels.resize(v.size());
  for (size_t i = 0; i < v.size(); ++i)
    n.texels[i] = uint8_t(std::lround((v[i] - *lo) / range * 255.0f));
  return n;
}

}  // namespace cb
