// A picture as the picture → cloud tool reads it (seed 002 §3.1.1): a PNG, checked from its
// header before any pixel is allocated, reduced to a binary shape mask. With an alpha channel
// the shape is where alpha ≥ 128; an opaque picture (a photo or a black-on-white silhouette) is
// split by Otsu's luminance threshold and the shape is the class touching the border less.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace cb {

constexpr long long kMaxPicturePixels = 4096LL * 4096LL;

struct ShapeMask {
  int width = 0, height = 0;
  std::vector<uint8_t> inside;  // width*height, row 0 at the top, 1 = shape
  bool at(int x, int y) const { return inside[size_t(y) * width + x] != 0; }
  long long count() const;
};

// Width and height from the PNG signature and IHDR chunk; throws ToolError (kUnreadableFile,
// kNotPng, kEmptyImage, kImageTooLarge) without decoding the picture.
void readPngSize(const std::string& path, int* width, int* height);
// readPngSize's checks, then the decode and the mask. kEmptyImage when no pixel is shape.
ShapeMask loadShapeMask(const std::string& path);
// The mask of already-decoded RGBA8 pixels (row 0 at the top).
ShapeMask shapeMaskFromRgba(int width, int height, const std::vector<uint8_t>& rgba);

}  // namespace cb
