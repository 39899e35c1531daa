// Fuzz target: the PNG reader as the sky image uses it ([sky] image: a picture from anywhere),
// with the size limit checked from the header before decoding. Any input either decodes to an
// image whose pixel buffer matches its size within the limit, or throws ImageIoError.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>

#include "app/render/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = "/tmp/cb_fuzz_sky_image_" + std::to_string(::getpid()) + ".png";
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  }
  constexpr int64_t kLimit = 1 << 20;  // small, so mutated headers hit the limit
  try {
    const cb::ImageRgba8 image = cb::readPng(path, kLimit);
    if (image.width <= 0 || image.height <= 0 || int64_t(image.width) * image.height > kLimit ||
        image.pixels.size() != size_t(image.width) * size_t(image.height) * 4)
      std::abort();
  } catch (const cb::ImageIoError&) {
  }
  return 0;
}
