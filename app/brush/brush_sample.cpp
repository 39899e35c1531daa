#include "app/brush/brush_sample.h"

#include <cmath>

namespace cb {

float BrushSample::bilinear(float x, float y) const {
  float fx = x - 0.5f, fy = y - 0.5f;
  float x0f = std::floor(fx), y0f = std::floor(fy);
  int x0 = int(x0f), y0 = int(y0f);
  float tx = fx - x0f, ty = fy - y0f;
  auto v = [&](int i, int j) {
    return (i < 0 || j < 0 || i >= size || j >= size) ? 0.0f : at(i, j);
  };
  float a = v(x0, y0) + (v(x0 + 1, y0) - v(x0, y0)) * tx;
  float b = v(x0, y0 + 1) + (v(x0 + 1, y0 + 1) - v(x0, y0 + 1)) * tx;
  return a + (b - a) * ty;
}

float BrushSample::sum() const {
  double s = 0.0;
  for (float v : values) s += v;
  return float(s);
}

}  // namespace cb
