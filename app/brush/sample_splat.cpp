#include "app/brush/sample_splat.h"

#include <algorithm>
#include <cmath>

namespace cb {

FootprintRect splatSample(const BrushSample& sample, const SplatParams& p,
                          const DispersionField& field, Footprint* fp) {
  if (sample.size == 0 || !(p.diameter_px > 0.0f)) return {};
  float half = 0.5f * p.diameter_px;
  FootprintRect r{int(std::floor(p.centre_px.x - half)), int(std::floor(p.centre_px.y - half)),
                  int(std::ceil(p.centre_px.x + half)) + 1,
                  int(std::ceil(p.centre_px.y + half)) + 1};
  r = r.clipped(fp->width, fp->height);
  if (r.empty()) return {};
  float texels_per_px = float(sample.size) / p.diameter_px;
  float origin_x = p.centre_px.x - half, origin_y = p.centre_px.y - half;
  bool touched = false;
  for (int y = r.y0; y < r.y1; ++y) {
    float sy = (y + 0.5f - origin_y) * texels_per_px;
    for (int x = r.x0; x < r.x1; ++x) {
      float sx = (x + 0.5f - origin_x) * texels_per_px;
      float v = sample.bilinear(sx, sy);
      if (v <= 0.0f) continue;
      v = std::min(1.0f, v * p.gain) * field.keep(x, y, p.dispersion);
      float& dst = fp->at(x, y);
      if (v > dst) {
        dst = v;
        touched = true;
      }
    }
  }
  return touched ? r : FootprintRect{};
}

FootprintRect splatDot(glm::vec2 c, float radius, float value, float dispersion,
                       const DispersionField& field, Footprint* fp) {
  FootprintRect r{int(std::floor(c.x - radius - 1.0f)), int(std::floor(c.y - radius - 1.0f)),
                  int(std::ceil(c.x + radius + 1.0f)) + 1, int(std::ceil(c.y + radius + 1.0f)) + 1};
  r = r.clipped(fp->width, fp->height);
  if (r.empty()) return {};
  bool touched = false;
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) {
      float d = std::hypot(x + 0.5f - c.x, y + 0.5f - c.y);
      float cover = std::clamp(radius + 0.5f - d, 0.0f, 1.0f);
      if (cover <= 0.0f) continue;
      float v = value * cover * field.keep(x, y, dispersion);
      float& dst = fp->at(x, y);
      if (v > dst) {
        dst = v;
        touched = true;
      }
    }
  return touched ? r : FootprintRect{};
}

}  // namespace cb
