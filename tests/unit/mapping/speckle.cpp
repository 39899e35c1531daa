#include "speckle.h"

#include <cstdlib>
#include <vector>

namespace cb::test {

float pixelLuminance(const uint8_t* p) {
  return (0.2126f * float(p[0]) + 0.7152f * float(p[1]) + 0.0722f * float(p[2])) / 255.0f;
}

bool differsFromEmpty(const uint8_t* p, const uint8_t* empty) {
  return std::abs(int(p[0]) - int(empty[0])) + std::abs(int(p[1]) - int(empty[1])) +
             std::abs(int(p[2]) - int(empty[2])) >
         12;
}

Speckle measureSpeckle(const ImageRgba8& image, const ImageRgba8& empty, float dark_luminance,
                       int max_island) {
  const int w = image.width, h = image.height;
  std::vector<uint8_t> dark(size_t(w) * size_t(h));
  Speckle s;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const uint8_t* p = image.at(x, y);
      const bool cloud = differsFromEmpty(p, empty.at(x, y));
      s.cloud += cloud;
      dark[size_t(y) * size_t(w) + size_t(x)] = cloud && pixelLuminance(p) < dark_luminance;
    }
  // Flood-fill each dark island (8-connected); islands of at most max_island pixels are specks.
  std::vector<int> stack, island;
  for (size_t start = 0; start < dark.size(); ++start) {
    if (dark[start] != 1) continue;
    dark[start] = 2;
    stack.assign(1, int(start));
    island.clear();
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      island.push_back(i);
      const int x = i % w, y = i / w;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int u = x + dx, v = y + dy;
          if (u < 0 || v < 0 || u >= w || v >= h) continue;
          const size_t j = size_t(v) * size_t(w) + size_t(u);
          if (dark[j] == 1) dark[j] = 2, stack.push_back(int(j));
        }
    }
    s.dark += long(island.size());
    ++s.islands;
    if (int(island.size()) <= max_island) s.speckle += long(island.size());
  }
  return s;
}

}  // namespace cb::test
