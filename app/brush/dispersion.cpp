#include "app/brush/dispersion.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <mutex>
#include <tuple>

#include "app/brush/hash_noise.h"

namespace cb {
namespace {
inline float smoothstep(float e0, float e1, float x) {
  float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}
constexpr float kEdgeWidth = 0.25f;  // softness of the dry/wet boundary in noise units
}  // namespace

float dispersionForSpeed(const DispersionParams& p, float speed) {
  if (!(speed > p.slow_speed_px_s)) return 0.0f;
  float span = std::max(p.fast_speed_px_s - p.slow_speed_px_s, 1e-3f);
  return p.max_dispersion * smoothstep(0.0f, 1.0f, (speed - p.slow_speed_px_s) / span);
}

namespace {

// Tileable value noise for one stroke: the pattern of dry and wet ink.
std::vector<float> dispersionNoise(uint32_t stroke_index, float noise_scale_px) {
  constexpr int kTile = DispersionField::kTile;
  std::vector<float> noise(size_t(kTile) * kTile);
  // Tileable value noise, three octaves: the lattice of each octave (period × period hashed
  // values, wrapping) is built first, then interpolated for every pixel of the tile.
  int period = std::max(1, int(std::lround(kTile / noise_scale_px)));
  uint32_t seed = hashCombine(0xd15e5u, int32_t(stroke_index));
  std::vector<float> sum(size_t(kTile) * kTile, 0.0f);
  float amplitude = 1.0f, norm = 0.0f;
  for (int octave = 0; octave < 3; ++octave, period *= 2, amplitude *= 0.5f) {
    std::vector<float> lattice(size_t(period) * period);
    for (int j = 0; j < period; ++j)
      for (int i = 0; i < period; ++i)
        lattice[size_t(j) * period + i] = unitFloat(hashCombine(seed + 101u * octave, i, j));
    float cells_per_px = float(period) / kTile;
    for (int y = 0; y < kTile; ++y) {
      float fy = (y + 0.5f) * cells_per_px;
      int j0 = int(fy) % period, j1 = (j0 + 1) % period;
      float ty = smoothstep(0.0f, 1.0f, fy - std::floor(fy));
      for (int x = 0; x < kTile; ++x) {
        float fx = (x + 0.5f) * cells_per_px;
        int i0 = int(fx) % period, i1 = (i0 + 1) % period;
        float tx = smoothstep(0.0f, 1.0f, fx - std::floor(fx));
        const float* r0 = &lattice[size_t(j0) * period];
        const float* r1 = &lattice[size_t(j1) * period];
        float top = r0[i0] + (r0[i1] - r0[i0]) * tx, bottom = r1[i0] + (r1[i1] - r1[i0]) * tx;
        sum[size_t(y) * kTile + x] += amplitude * (top + (bottom - top) * ty);
      }
    }
    norm += amplitude;
  }
  // Stretch the fractal sum (which bunches around 0.5) back over 0..1.
  for (size_t i = 0; i < sum.size(); ++i)
    noise[i] = std::clamp((sum[i] / norm - 0.5f) * 2.2f + 0.5f, 0.0f, 1.0f);
  return noise;
}

}  // namespace

void DispersionField::reset(uint32_t stroke_index, float noise_scale_px) {
  if (noise_ && stroke_index == stroke_index_ && noise_scale_px == scale_) return;
  stroke_index_ = stroke_index;
  scale_ = noise_scale_px;
  static std::mutex mutex;
  static std::deque<std::tuple<uint32_t, float, std::shared_ptr<const std::vector<float>>>> kept;
  std::lock_guard<std::mutex> lock(mutex);
  for (const auto& [index, scale, noise] : kept)
    if (index == stroke_index && scale == noise_scale_px) return void(noise_ = noise);
  noise_ =
      std::make_shared<const std::vector<float>>(dispersionNoise(stroke_index, noise_scale_px));
  kept.emplace_back(stroke_index, noise_scale_px, noise_);
  if (kept.size() > 8) kept.pop_front();
}

float DispersionField::keep(int x, int y, float d) const {
  if (d <= 0.0f || !noise_) return 1.0f;
  float n = (*noise_)[size_t(y & (kTile - 1)) * kTile + (x & (kTile - 1))];
  return smoothstep(d - kEdgeWidth, d, n);
}

}  // namespace cb
