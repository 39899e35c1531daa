#include "app/brush/dispersion.h"

#include <algorithm>
#include <cmath>

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

void DispersionField::reset(uint32_t stroke_index, float noise_scale_px) {
  if (!noise_.empty() && stroke_index == stroke_index_ && noise_scale_px == scale_) return;
  stroke_index_ = stroke_index;
  scale_ = noise_scale_px;
  noise_.resize(size_t(kTile) * kTile);
  // Tileable: the lattice period is the tile size in noise cells.
  int period = std::max(1, int(std::lround(kTile / noise_scale_px)));
  float cells_per_px = float(period) / kTile;
  uint32_t seed = hashCombine(0xd15e5u, int32_t(stroke_index));
  for (int y = 0; y < kTile; ++y)
    for (int x = 0; x < kTile; ++x) {
      float n =
          fractalNoise2D((x + 0.5f) * cells_per_px, (y + 0.5f) * cells_per_px, 3, seed, period);
      // Stretch the fractal sum (which bunches around 0.5) back over 0..1.
      noise_[size_t(y) * kTile + x] = std::clamp((n - 0.5f) * 2.2f + 0.5f, 0.0f, 1.0f);
    }
}

float DispersionField::keep(int x, int y, float d) const {
  if (d <= 0.0f || noise_.empty()) return 1.0f;
  float n = noise_[size_t(y & (kTile - 1)) * kTile + (x & (kTile - 1))];
  return smoothstep(d - kEdgeWidth, d, n);
}

}  // namespace cb
