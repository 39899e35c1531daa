// RGBA images in memory (row 0 at the top), PNG and OpenEXR files, and readback of a GL
// framebuffer (which stores row 0 at the bottom) into them.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/render/gl/gl.h"

namespace cb {

struct ImageIoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// 8-bit RGBA, row-major, row 0 at the top.
struct ImageRgba8 {
  int width = 0, height = 0;
  std::vector<uint8_t> pixels;  // width*height*4
  uint8_t* at(int x, int y) { return &pixels[(size_t(y) * width + x) * 4]; }
  const uint8_t* at(int x, int y) const { return &pixels[(size_t(y) * width + x) * 4]; }
};

// Linear float RGBA, row-major, row 0 at the top.
struct ImageRgbaF {
  int width = 0, height = 0;
  std::vector<float> pixels;  // width*height*4
};

// Write / read 8-bit RGBA PNG (libpng). Errors name the file and the problem. readPng checks
// the header's size against kMaxPngSide before it allocates the pixels.
inline constexpr uint32_t kMaxPngSide = 16384;
void writePng(const std::string& path, const ImageRgba8& image);
// An 8-bit palette PNG of at most 256 colours, for pictures kept in the repository (contact
// sheets): the 256 most frequent colours at 5 bits per channel (their pixels' means) and each
// pixel as its nearest; alpha is dropped (opaque). Deterministic: the same image, the same bytes.
void writePngPalette(const std::string& path, const ImageRgba8& image);
// readPng refuses (before decoding) an image of more than max_pixels pixels when max_pixels > 0.
ImageRgba8 readPng(const std::string& path, int64_t max_pixels = 0);
// Write a float RGBA OpenEXR file (32-bit float channels, ZIP compression).
void writeExr(const std::string& path, const ImageRgbaF& image);
// writePng or writeExr by the extension (.png / .exr); anything else is an error.
void writeImageByExtension(const std::string& path, const ImageRgba8& rgba8,
                           const ImageRgbaF& rgbaf);

// Reads the colour attachment 0 of `fbo` (bound for reading) into an image, flipped so row 0 is
// the top. Needs a current GL context.
ImageRgba8 readFramebufferRgba8(GLuint fbo, int width, int height);
ImageRgbaF readFramebufferRgbaF(GLuint fbo, int width, int height);

}  // namespace cb
