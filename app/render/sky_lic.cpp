#include "app/render/sky_lic.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "app/core/parallel_for.h"

namespace cb {
namespace {

constexpr float kTwoPi = 6.28318530718f;

// SplitMix64 finaliser: a value per (seed, stream, index), independent of evaluation order.
uint64_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

float uniform01(uint32_t seed, uint32_t stream, uint64_t index) {
  const uint64_t h = mix64((uint64_t(seed) << 32 | stream) * 0x9e3779b97f4a7c15ull + index);
  return float(h >> 40) / float(1 << 24);
}

int wrap(int i, int n) {
  i %= n;
  return i < 0 ? i + n : i;
}

float smooth01(float t) {
  return t * t * (3.0f - 2.0f * t);
}

// Periodic value noise with `cells` cells across a texture of `size` texels (a seeded lattice,
// smoothstep-interpolated, wrapping).
float valueNoise(glm::vec2 p, int size, int cells, uint32_t seed, uint32_t stream) {
  const glm::vec2 q = p / float(size) * float(cells);
  const glm::vec2 i0 = glm::floor(q);
  const glm::vec2 f = q - i0;
  auto lattice = [&](int x, int y) {
    return uniform01(seed, stream,
                     uint64_t(wrap(y, cells)) * uint64_t(cells) + uint64_t(wrap(x, cells)));
  };
  const int x = int(i0.x), y = int(i0.y);
  const float a = glm::mix(lattice(x, y), lattice(x + 1, y), smooth01(f.x));
  const float b = glm::mix(lattice(x, y + 1), lattice(x + 1, y + 1), smooth01(f.x));
  return glm::mix(a, b, smooth01(f.y));
}

// The flow field sampled at texel centres (licFlow), interpolated bilinearly and renormalised.
struct FlowGrid {
  int size = 0;
  std::vector<glm::vec2> v;
  glm::vec2 at(glm::vec2 p) const {
    const glm::vec2 u = p - 0.5f;
    const glm::vec2 i0 = glm::floor(u);
    const glm::vec2 f = u - i0;
    const int x = int(i0.x), y = int(i0.y);
    auto g = [&](int xx, int yy) {
      return v[size_t(wrap(yy, size)) * size_t(size) + size_t(wrap(xx, size))];
    };
    const glm::vec2 s = glm::mix(glm::mix(g(x, y), g(x + 1, y), f.x),
                                 glm::mix(g(x, y + 1), g(x + 1, y + 1), f.x), f.y);
    const float len = glm::length(s);
    return len > 1e-6f ? s / len : glm::vec2(1.0f, 0.0f);
  }
};

void checkSize(int size, int length) {
  if (size < 16 || size > 4096)
    throw std::invalid_argument("LIC sky texture size " + std::to_string(size) +
                                " is outside [16, 4096]");
  if (length < 1 || length > 256)
    throw std::invalid_argument("LIC streak length " + std::to_string(length) +
                                " is outside [1, 256]");
}

}  // namespace

float ScalarImage::at(int x, int y) const {
  return values[size_t(wrap(y, size)) * size_t(size) + size_t(wrap(x, size))];
}

float ScalarImage::bilinear(glm::vec2 p) const {
  const glm::vec2 u = p - 0.5f;
  const glm::vec2 i0 = glm::floor(u);
  const glm::vec2 f = u - i0;
  const int x = int(i0.x), y = int(i0.y);
  return glm::mix(glm::mix(at(x, y), at(x + 1, y), f.x),
                  glm::mix(at(x, y + 1), at(x + 1, y + 1), f.x), f.y);
}

ScalarImage whiteNoise(int size, uint32_t seed) {
  ScalarImage n;
  n.size = size;
  n.values.resize(size_t(size) * size_t(size));
  for (size_t i = 0; i < n.values.size(); ++i) n.values[i] = uniform01(seed, 1, i);
  return n;
}

glm::vec2 licFlow(glm::vec2 p, int size, uint32_t seed) {
  // Prevailing wind angle and three eddies with integer wave vectors (so the field is periodic
  // with the texture), each bending the angle by up to 0.45 rad.
  float angle = kTwoPi * uniform01(seed, 2, 0);
  const glm::vec2 q = p / float(size) * kTwoPi;
  for (uint64_t k = 0; k < 3; ++k) {
    const float mx = float(1 + int(3.0f * uniform01(seed, 3, 2 * k)));
    const float my = float(1 + int(3.0f * uniform01(seed, 3, 2 * k + 1)));
    const float phase = kTwoPi * uniform01(seed, 4, k);
    angle += 0.45f * std::sin(mx * q.x + my * q.y + phase);
  }
  return {std::cos(angle), std::sin(angle)};
}

ScalarImage lineIntegralConvolution(const ScalarImage& source, int length, uint32_t seed) {
  checkSize(source.size, length);
  const int size = source.size;
  FlowGrid flow;
  flow.size = size;
  flow.v.resize(size_t(size) * size_t(size));
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      flow.v[size_t(y) * size_t(size) + size_t(x)] =
          licFlow(glm::vec2(float(x) + 0.5f, float(y) + 0.5f), size, seed);
  ScalarImage out;
  out.size = size;
  out.values.resize(source.values.size());
  const float norm = 1.0f / float(2 * length + 1);
  // Each texel is independent of the others: same bytes on any thread count.
  parallelFor(size_t(size), 8, [&](size_t, size_t y0, size_t y1) {
    for (size_t y = y0; y < y1; ++y)
      for (int x = 0; x < size; ++x) {
        const glm::vec2 start(float(x) + 0.5f, float(y) + 0.5f);
        float sum = source.bilinear(start);
        for (float direction : {1.0f, -1.0f}) {
          glm::vec2 p = start;
          for (int i = 0; i < length; ++i) {
            // Midpoint step of unit length along the streamline (Fig. 7: forward and backward).
            const glm::vec2 mid = p + 0.5f * direction * flow.at(p);
            p += direction * flow.at(mid);
            sum += source.bilinear(p);
          }
        }
        out.values[y * size_t(size) + size_t(x)] = sum * norm;
      }
  });
  return out;
}

std::vector<uint8_t> makeLicSkyTexture(int size, int length, float coverage, uint32_t seed) {
  checkSize(size, length);
  ScalarImage lic = lineIntegralConvolution(whiteNoise(size, seed), length, seed);
  // Averaging 2L+1 noise samples shrinks their spread; restore it (in a fixed order, so the
  // result does not depend on threads) to a standard deviation of 0.2 around 0.5.
  double mean = 0.0, square = 0.0;
  for (float v : lic.values) {
    mean += v;
    square += double(v) * v;
  }
  mean /= double(lic.values.size());
  const double sd = std::sqrt(std::max(square / double(lic.values.size()) - mean * mean, 1e-12));
  for (float& v : lic.values) v = std::clamp(0.5f + float((v - mean) / sd) * 0.2f, 0.0f, 1.0f);
  // Seed 002 §3.2.2 smooths its LIC results by iteration: two 3×3 box passes (wrapping).
  for (int pass = 0; pass < 2; ++pass) {
    ScalarImage blurred = lic;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        float s = 0.0f;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) s += lic.at(x + dx, y + dy);
        blurred.values[size_t(y) * size_t(size) + size_t(x)] = s / 9.0f;
      }
    lic = std::move(blurred);
  }
  // Patches: a low-frequency coverage field decides where the layer is; inside, the streaks
  // modulate its opacity, and they also fray the patches' edges.
  std::vector<uint8_t> texels(size_t(size) * size_t(size));
  const float threshold = 1.0f - std::clamp(coverage, 0.0f, 1.0f);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const glm::vec2 p(float(x) + 0.5f, float(y) + 0.5f);
      const float cover =
          0.65f * valueNoise(p, size, 4, seed, 5) + 0.35f * valueNoise(p, size, 9, seed, 6);
      const float streak = lic.at(x, y);
      const float patch = cover + 0.35f * (streak - 0.5f);
      const float t = std::clamp((patch - threshold + 0.12f) / 0.3f, 0.0f, 1.0f);
      const float opacity = smooth01(t) * std::clamp(0.35f + 1.3f * (streak - 0.3f), 0.0f, 1.0f);
      texels[size_t(y) * size_t(size) + size_t(x)] = uint8_t(std::lround(opacity * 255.0f));
    }
  return texels;
}

}  // namespace cb
