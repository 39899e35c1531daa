#include "app/tools/silhouette_image.h"

#include <array>
#include <cstring>
#include <fstream>

#include "app/render/image_io.h"
#include "app/tools/tool_error.h"

namespace cb {

long long ShapeMask::count() const {
  long long n = 0;
  for (uint8_t v : inside) n += v;
  return n;
}

void readPngSize(const std::string& path, int* width, int* height) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ToolError(ToolErrorKind::kUnreadableFile, path + ": cannot open");
  std::array<unsigned char, 24> head{};
  in.read(reinterpret_cast<char*>(head.data()), head.size());
  const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (in.gcount() < 24 || std::memcmp(head.data(), kSignature, 8) != 0 ||
      std::memcmp(head.data() + 12, "IHDR", 4) != 0)
    throw ToolError(ToolErrorKind::kNotPng, path + ": no PNG signature and IHDR header");
  auto be32 = [&](int at) {
    return (uint32_t(head[at]) << 24) | (uint32_t(head[at + 1]) << 16) |
           (uint32_t(head[at + 2]) << 8) | uint32_t(head[at + 3]);
  };
  const uint32_t w = be32(16), h = be32(20);
  if (w == 0 || h == 0)
    throw ToolError(ToolErrorKind::kEmptyImage,
                    path + ": header says " + std::to_string(w) + "x" + std::to_string(h));
  if ((long long)w * (long long)h > kMaxPicturePixels || w > 65535 || h > 65535)
    throw ToolError(ToolErrorKind::kImageTooLarge,
                    path + ": header says " + std::to_string(w) + "x" + std::to_string(h) +
                        ", limit " + std::to_string(kMaxPicturePixels) + " pixels");
  *width = int(w);
  *height = int(h);
}

ShapeMask shapeMaskFromRgba(int width, int height, const std::vector<uint8_t>& rgba) {
  ShapeMask mask;
  mask.width = width;
  mask.height = height;
  const size_t n = size_t(width) * size_t(height);
  mask.inside.assign(n, 0);
  bool has_alpha = false;
  for (size_t i = 0; i < n && !has_alpha; ++i) has_alpha = rgba[i * 4 + 3] < 255;
  if (has_alpha) {
    for (size_t i = 0; i < n; ++i) mask.inside[i] = rgba[i * 4 + 3] >= 128;
    return mask;
  }
  // Otsu's threshold on Rec. 601 luminance.
  std::vector<uint8_t> luma(n);
  std::array<long long, 256> hist{};
  for (size_t i = 0; i < n; ++i) {
    const uint8_t* p = &rgba[i * 4];
    luma[i] = uint8_t((299 * p[0] + 587 * p[1] + 114 * p[2] + 500) / 1000);
    ++hist[luma[i]];
  }
  double sum_all = 0;
  for (int v = 0; v < 256; ++v) sum_all += double(v) * double(hist[v]);
  double best = -1, sum_below = 0;
  long long count_below = 0;
  int threshold = 128;
  for (int v = 0; v < 255; ++v) {
    count_below += hist[v];
    sum_below += double(v) * double(hist[v]);
    const long long count_above = (long long)n - count_below;
    if (count_below == 0 || count_above == 0) continue;
    const double mb = sum_below / double(count_below);
    const double ma = (sum_all - sum_below) / double(count_above);
    const double between = double(count_below) * double(count_above) * (mb - ma) * (mb - ma);
    if (between > best) {
      best = between;
      threshold = v;  // dark class: luma <= threshold
    }
  }
  long long dark_border = 0, border = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      if (x != 0 && y != 0 && x != width - 1 && y != height - 1) continue;
      ++border;
      dark_border += luma[size_t(y) * width + x] <= threshold;
    }
  const bool shape_is_dark = 2 * dark_border <= border;
  for (size_t i = 0; i < n; ++i)
    mask.inside[i] = shape_is_dark ? (luma[i] <= threshold) : (luma[i] > threshold);
  return mask;
}

ShapeMask loadShapeMask(const std::string& path) {
  int w = 0, h = 0;
  readPngSize(path, &w, &h);
  ImageRgba8 image;
  try {
    image = readPng(path);
  } catch (const std::exception& e) {
    throw ToolError(ToolErrorKind::kNotPng, e.what());
  }
  ShapeMask mask = shapeMaskFromRgba(image.width, image.height, image.pixels);
  if (mask.count() == 0)
    throw ToolError(ToolErrorKind::kEmptyImage, path + ": no shape pixel in the picture");
  return mask;
}

}  // namespace cb
