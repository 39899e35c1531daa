#include "app/mapping/simplex_noise.h"

#include <algorithm>
#include <cmath>
#include <mutex>

#include "app/core/parallel_for.h"

namespace cb {
namespace {

const int kGrad3[12][3] = {{1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0},
                           {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
                           {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}};

// SplitMix64: a small, well-mixed generator for shuffling the permutation.
uint64_t splitMix64(uint64_t* state) {
  uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

float corner(const uint8_t* perm, int i, int j, int k, float x, float y, float z) {
  float t = 0.6f - x * x - y * y - z * z;
  if (t < 0.0f) return 0.0f;
  const int* g = kGrad3[perm[i + perm[j + perm[k]]] % 12];
  t *= t;
  return t * t * (float(g[0]) * x + float(g[1]) * y + float(g[2]) * z);
}

}  // namespace

SimplexNoise3::SimplexNoise3(uint32_t seed) {
  std::array<uint8_t, 256> p;
  for (int i = 0; i < 256; ++i) p[i] = uint8_t(i);
  uint64_t state = seed;
  for (int i = 255; i > 0; --i) std::swap(p[i], p[splitMix64(&state) % uint64_t(i + 1)]);
  for (int i = 0; i < 512; ++i) perm_[i] = p[i & 255];
}

float SimplexNoise3::operator()(glm::vec3 pos) const {
  // Skew to the simplex lattice (F3 = 1/3, G3 = 1/6).
  constexpr float F3 = 1.0f / 3.0f, G3 = 1.0f / 6.0f;
  float s = (pos.x + pos.y + pos.z) * F3;
  int i = int(std::floor(pos.x + s)), j = int(std::floor(pos.y + s)),
      k = int(std::floor(pos.z + s));
  float t = float(i + j + k) * G3;
  float x0 = pos.x - (float(i) - t), y0 = pos.y - (float(j) - t), z0 = pos.z - (float(k) - t);
  int i1, j1, k1, i2, j2, k2;
  if (x0 >= y0) {
    if (y0 >= z0)
      i1 = 1, j1 = 0, k1 = 0, i2 = 1, j2 = 1, k2 = 0;
    else if (x0 >= z0)
      i1 = 1, j1 = 0, k1 = 0, i2 = 1, j2 = 0, k2 = 1;
    else
      i1 = 0, j1 = 0, k1 = 1, i2 = 1, j2 = 0, k2 = 1;
  } else {
    if (y0 < z0)
      i1 = 0, j1 = 0, k1 = 1, i2 = 0, j2 = 1, k2 = 1;
    else if (x0 < z0)
      i1 = 0, j1 = 1, k1 = 0, i2 = 0, j2 = 1, k2 = 1;
    else
      i1 = 0, j1 = 1, k1 = 0, i2 = 1, j2 = 1, k2 = 0;
  }
  const int ii = i & 255, jj = j & 255, kk = k & 255;
  const uint8_t* p = perm_.data();
  float n = corner(p, ii, jj, kk, x0, y0, z0);
  n += corner(p, ii + i1, jj + j1, kk + k1, x0 - i1 + G3, y0 - j1 + G3, z0 - k1 + G3);
  n += corner(p, ii + i2, jj + j2, kk + k2, x0 - i2 + 2 * G3, y0 - j2 + 2 * G3, z0 - k2 + 2 * G3);
  n += corner(p, ii + 1, jj + 1, kk + 1, x0 - 1 + 3 * G3, y0 - 1 + 3 * G3, z0 - 1 + 3 * G3);
  return 32.0f * n;
}

NoiseTexture::NoiseTexture(const NoiseTextureConfig& cfg) : size_(cfg.size) {
  const SimplexNoise3 noise(cfg.seed);
  const int n = size_;
  std::vector<float> raw(size_t(n) * n * n);
  // fBm of simplex noise, made periodic: f_p(x) = Σ_corners w(x) f(x - corner * n).
  auto fbm = [&](glm::vec3 p) {
    float sum = 0.0f, amp = 1.0f, norm = 0.0f, freq = 1.0f / cfg.period_voxels;
    for (int o = 0; o < cfg.octaves; ++o) {
      sum += amp * noise(p * freq + glm::vec3(float(o) * 17.31f));
      norm += amp;
      amp *= 0.5f;
      freq *= 2.0f;
    }
    return sum / norm;
  };
  parallelFor(size_t(n), 4, [&](size_t, size_t z0, size_t z1) {
    for (size_t z = z0; z < z1; ++z)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const glm::vec3 p{float(x), float(y), float(z)};
          glm::vec3 w = p / float(n);  // blend weights towards the shifted copies
          float v = 0.0f;
          for (int c = 0; c < 8; ++c) {
            glm::vec3 s((c & 1) ? 1.0f : 0.0f, (c & 2) ? 1.0f : 0.0f, (c & 4) ? 1.0f : 0.0f);
            float wx = s.x ? w.x : 1.0f - w.x, wy = s.y ? w.y : 1.0f - w.y,
                  wz = s.z ? w.z : 1.0f - w.z;
            v += wx * wy * wz * fbm(p - s * float(n));
          }
          raw[(z * n + size_t(y)) * n + size_t(x)] = v;
        }
  });
  // Remap to [0, 1] by the texture's own range (deterministic: a serial min/max).
  auto [lo, hi] = std::minmax_element(raw.begin(), raw.end());
  const float a = *lo, range = std::max(1e-6f, *hi - *lo);
  texels_.resize(raw.size());
  for (size_t i = 0; i < raw.size(); ++i) texels_[i] = (raw[i] - a) / range;
}

std::shared_ptr<const NoiseTexture> sharedNoiseTexture(const NoiseTextureConfig& config) {
  struct Entry {
    NoiseTextureConfig config;
    std::shared_ptr<const NoiseTexture> texture;
  };
  static std::mutex mutex;
  static std::vector<Entry> made;  // one per distinct config (a process sees one or two)
  std::lock_guard<std::mutex> lock(mutex);
  for (const Entry& e : made)
    if (e.config.seed == config.seed && e.config.size == config.size &&
        e.config.period_voxels == config.period_voxels && e.config.octaves == config.octaves)
      return e.texture;
  made.push_back({config, std::make_shared<const NoiseTexture>(config)});
  return made.back().texture;
}

}  // namespace cb
