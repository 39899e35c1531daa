#include "line_measures.h"

#include <cstdlib>
#include <vector>

#include "speckle.h"

namespace cb::test {
namespace {

struct Masks {
  int w = 0, h = 0;
  std::vector<uint8_t> cloud, dark;
  bool at(const std::vector<uint8_t>& m, int x, int y) const {
    return x >= 0 && y >= 0 && x < w && y < h && m[size_t(y) * size_t(w) + size_t(x)];
  }
};

// The cloud from `extent` against `extent_empty`, the dark pixels from `image` (anywhere: an
// outline may be drawn just outside the silhouette).
Masks masksOf(const ImageRgba8& image, const ImageRgba8& extent, const ImageRgba8& extent_empty,
              float dark_luminance) {
  Masks m;
  m.w = image.width;
  m.h = image.height;
  m.cloud.resize(size_t(m.w) * size_t(m.h));
  m.dark.resize(m.cloud.size());
  for (int y = 0; y < m.h; ++y)
    for (int x = 0; x < m.w; ++x) {
      const size_t i = size_t(y) * size_t(m.w) + size_t(x);
      m.cloud[i] = differsFromEmpty(extent.at(x, y), extent_empty.at(x, y));
      m.dark[i] = pixelLuminance(image.at(x, y)) < dark_luminance;
    }
  return m;
}

bool anyInWindow(const Masks& m, const std::vector<uint8_t>& mask, int x, int y, int r) {
  for (int v = y - r; v <= y + r; ++v)
    for (int u = x - r; u <= x + r; ++u)
      if (m.at(mask, u, v)) return true;
  return false;
}

}  // namespace

OutlineBreaks measureOutlineBreaks(const ImageRgba8& image, const ImageRgba8& extent,
                                   const ImageRgba8& extent_empty, float dark_luminance,
                                   int reach) {
  const Masks m = masksOf(image, extent, extent_empty, dark_luminance);
  OutlineBreaks b;
  for (int y = 0; y < m.h; ++y)
    for (int x = 0; x < m.w; ++x) {
      if (!m.at(m.cloud, x, y)) continue;
      const bool edge = !m.at(m.cloud, x - 1, y) || !m.at(m.cloud, x + 1, y) ||
                        !m.at(m.cloud, x, y - 1) || !m.at(m.cloud, x, y + 1);
      if (!edge) continue;
      ++b.edge;
      b.broken += !anyInWindow(m, m.dark, x, y, reach);
    }
  return b;
}

SolidPatches measureSolidPatches(const ImageRgba8& image, const ImageRgba8& extent,
                                 const ImageRgba8& extent_empty, float dark_luminance, int radius) {
  const Masks m = masksOf(image, extent, extent_empty, dark_luminance);
  SolidPatches s;
  for (int y = 0; y < m.h; ++y)
    for (int x = 0; x < m.w; ++x) {
      if (!m.at(m.cloud, x, y)) continue;
      ++s.cloud;
      bool solid = true;
      for (int v = y - radius; v <= y + radius && solid; ++v)
        for (int u = x - radius; u <= x + radius && solid; ++u) solid = m.at(m.dark, u, v);
      s.solid += solid;
    }
  return s;
}

}  // namespace cb::test
