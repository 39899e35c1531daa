#include "app/study/render_export.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <system_error>

namespace cb {

float srgbToLinear(float encoded) {
  const float c = std::max(encoded, 0.0f);
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

ImageRgbaF linearFromDisplayEncoded(const ImageRgbaF& display) {
  ImageRgbaF linear = display;
  for (size_t i = 0; i + 3 < linear.pixels.size(); i += 4)
    for (size_t c = 0; c < 3; ++c) linear.pixels[i + c] = srgbToLinear(display.pixels[i + c]);
  return linear;
}

ImageRgba8 quantiseDisplay(const ImageRgbaF& display) {
  ImageRgba8 image;
  image.width = display.width;
  image.height = display.height;
  image.pixels.resize(display.pixels.size());
  for (size_t i = 0; i < display.pixels.size(); ++i) {
    const float v =
        std::isfinite(display.pixels[i]) ? std::clamp(display.pixels[i], 0.0f, 1.0f) : 0.0f;
    image.pixels[i] = static_cast<uint8_t>(std::lround(v * 255.0f));
  }
  return image;
}

std::vector<std::string> exportRender(const ImageRgbaF& display_frame, const std::string& dir,
                                      const std::string& stem) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw ImageIoError(dir + ": cannot create the directory: " + ec.message());
  const std::filesystem::path base = std::filesystem::path(dir) / stem;
  const std::string exr = base.string() + ".exr";
  const std::string png = base.string() + ".png";
  writeExr(exr, linearFromDisplayEncoded(display_frame));
  writePng(png, quantiseDisplay(display_frame));
  return {exr, png};
}

}  // namespace cb
