#include "tests/unit/tools/tool_test_shapes.h"

#include <fstream>

namespace cb::test {

std::vector<uint8_t> cloudSilhouetteRgba(int width, int height) {
  struct Disc {
    float x, y, r;  // fractions of the width / height / shorter side
  };
  const Disc discs[] = {{0.30f, 0.62f, 0.20f}, {0.50f, 0.45f, 0.28f}, {0.70f, 0.60f, 0.20f},
                        {0.40f, 0.70f, 0.16f}, {0.62f, 0.72f, 0.15f}, {0.82f, 0.70f, 0.10f}};
  const float side = float(std::min(width, height));
  std::vector<uint8_t> rgba(size_t(width) * height * 4, 255);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      bool in = false;
      for (const Disc& d : discs) {
        const float dx = (x + 0.5f) - d.x * width, dy = (y + 0.5f) - d.y * height;
        in = in || dx * dx + dy * dy <= (d.r * side) * (d.r * side);
      }
      if (in) {
        uint8_t* p = &rgba[(size_t(y) * width + x) * 4];
        p[0] = p[1] = p[2] = 20;
      }
    }
  return rgba;
}

void writePngHeaderOnly(const std::string& path, uint32_t width, uint32_t height) {
  std::ofstream out(path, std::ios::binary);
  const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  out.write(reinterpret_cast<const char*>(sig), 8);
  const unsigned char len[4] = {0, 0, 0, 13};
  out.write(reinterpret_cast<const char*>(len), 4);
  out.write("IHDR", 4);
  for (uint32_t v : {width, height}) {
    const unsigned char b[4] = {uint8_t(v >> 24), uint8_t(v >> 16), uint8_t(v >> 8), uint8_t(v)};
    out.write(reinterpret_cast<const char*>(b), 4);
  }
  const unsigned char rest[5 + 4] = {8, 6, 0, 0, 0, 0, 0, 0, 0};  // depth, RGBA, …, fake CRC
  out.write(reinterpret_cast<const char*>(rest), sizeof rest);
}

}  // namespace cb::test
