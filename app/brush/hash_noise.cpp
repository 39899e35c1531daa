#include "app/brush/hash_noise.h"

#include <cmath>

namespace cb {
namespace {

inline float smooth(float t) {
  return t * t * (3.0f - 2.0f * t);
}
inline float lerp(float a, float b, float t) {
  return a + (b - a) * t;
}
inline int wrap(int i, int period) {
  if (period <= 0) return i;
  int m = i % period;
  return m < 0 ? m + period : m;
}

}  // namespace

uint32_t hashCombine(uint32_t seed, int32_t a, int32_t b, int32_t c) {
  uint32_t h = hashU32(seed ^ 0x85ebca6bu);
  h = hashU32(h ^ uint32_t(a));
  h = hashU32(h ^ (uint32_t(b) * 0x27d4eb2fu));
  h = hashU32(h ^ (uint32_t(c) * 0x165667b1u));
  return h;
}

float valueNoise2D(float x, float y, uint32_t seed, int period) {
  float fx = std::floor(x), fy = std::floor(y);
  int ix = int(fx), iy = int(fy);
  float tx = smooth(x - fx), ty = smooth(y - fy);
  auto v = [&](int i, int j) {
    return unitFloat(hashCombine(seed, wrap(ix + i, period), wrap(iy + j, period)));
  };
  return lerp(lerp(v(0, 0), v(1, 0), tx), lerp(v(0, 1), v(1, 1), tx), ty);
}

float valueNoise3D(float x, float y, float z, uint32_t seed) {
  float fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
  int ix = int(fx), iy = int(fy), iz = int(fz);
  float tx = smooth(x - fx), ty = smooth(y - fy), tz = smooth(z - fz);
  auto v = [&](int i, int j, int k) {
    return unitFloat(hashCombine(seed, ix + i, iy + j, iz + k));
  };
  float a = lerp(lerp(v(0, 0, 0), v(1, 0, 0), tx), lerp(v(0, 1, 0), v(1, 1, 0), tx), ty);
  float b = lerp(lerp(v(0, 0, 1), v(1, 0, 1), tx), lerp(v(0, 1, 1), v(1, 1, 1), tx), ty);
  return lerp(a, b, tz);
}

float fractalNoise2D(float x, float y, int octaves, uint32_t seed, int period) {
  float sum = 0.0f, amp = 1.0f, norm = 0.0f;
  for (int o = 0; o < octaves; ++o) {
    sum += amp * valueNoise2D(x, y, seed + uint32_t(o) * 101u, period);
    norm += amp;
    x *= 2.0f;
    y *= 2.0f;
    if (period > 0) period *= 2;
    amp *= 0.5f;
  }
  return sum / norm;
}

float fractalNoise3D(float x, float y, float z, int octaves, uint32_t seed) {
  float sum = 0.0f, amp = 1.0f, norm = 0.0f;
  for (int o = 0; o < octaves; ++o) {
    sum += amp * valueNoise3D(x, y, z, seed + uint32_t(o) * 101u);
    norm += amp;
    x *= 2.0f;
    y *= 2.0f;
    z *= 2.0f;
    amp *= 0.5f;
  }
  return sum / norm;
}

}  // namespace cb
