// A 2D brush sample (the thesis's "footprint sample", Fig. 5.6): a small square float image that
// is splatted onto the stroke's footprint centred on the pen tip. Row 0 is the top (−y of the
// footprint), values 0..1.
#pragma once

#include <cstddef>
#include <vector>

namespace cb {

struct BrushSample {
  int size = 0;
  std::vector<float> values;  // size × size, row-major

  BrushSample() = default;
  explicit BrushSample(int n) : size(n), values(size_t(n) * n, 0.0f) {}
  float at(int x, int y) const { return values[size_t(y) * size + x]; }
  float& at(int x, int y) { return values[size_t(y) * size + x]; }
  // Bilinear lookup at texel coordinates (texel centres at integer + 0.5); 0 outside.
  float bilinear(float x, float y) const;
  float sum() const;
};

}  // namespace cb
