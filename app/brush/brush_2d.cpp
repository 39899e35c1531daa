#include "app/brush/brush_2d.h"

#include <algorithm>
#include <cmath>

#include "app/brush/hash_noise.h"
#include "app/brush/sample_splat.h"

namespace cb {

BrushSample makeBristleTexture(const Brush2DParams& p) {
  BrushSample tex(p.texture_size);
  float n = float(p.texture_size);
  float disc_radius = 0.5f * n - 1.0f;
  SeededRandom rng(p.texture_seed);
  for (int i = 0; i < p.bristles; ++i) {
    // Uniform over the disc (sqrt of a uniform radius), a little denser towards the centre.
    float r = disc_radius * std::pow(rng.uniform(), 0.6f);
    float a = rng.uniform(0.0f, 6.2831853f);
    float cx = 0.5f * n + r * std::cos(a), cy = 0.5f * n + r * std::sin(a);
    float spot = n * rng.uniform(0.025f, 0.06f);
    float ink = rng.uniform(0.6f, 1.0f) * (1.0f - 0.35f * r / disc_radius);
    int x0 = std::max(0, int(cx - spot - 1)), x1 = std::min(p.texture_size, int(cx + spot + 2));
    int y0 = std::max(0, int(cy - spot - 1)), y1 = std::min(p.texture_size, int(cy + spot + 2));
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        float d = std::hypot(x + 0.5f - cx, y + 0.5f - cy);
        float v = ink * std::clamp((spot - d) / (0.5f * spot), 0.0f, 1.0f);
        tex.at(x, y) = std::max(tex.at(x, y), v);
      }
  }
  return tex;
}

Brush2D::Brush2D(const BrushConfig& c)
    : TextureBrush(c.stroke, c.dispersion, c.brush2d.max_diameter_px),
      params_(c.brush2d),
      texture_(makeBristleTexture(c.brush2d)) {}

float Brush2D::diameterFor(float pressure) const {
  return params_.min_diameter_px +
         (params_.max_diameter_px - params_.min_diameter_px) * std::clamp(pressure, 0.0f, 1.0f);
}

FootprintRect Brush2D::stampDab(const Dab& dab, float dispersion, Footprint* fp) {
  SplatParams splat;
  splat.centre_px = dab.footprint_px;
  // Tilt deliberately ignored (§5.3.1); the edge billows along the stroke.
  splat.diameter_px = diameterFor(dab.pressure) * dab.size_factor;
  splat.dispersion = dispersion;
  return splatSample(texture_, splat, dispersionField(), fp);
}

}  // namespace cb
