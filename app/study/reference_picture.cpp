#include "app/study/reference_picture.h"

namespace cb {

ImageRgba8 referencePictureForDisplay(const ImageRgba8& picture,
                                      const std::array<uint8_t, 3>& background) {
  ImageRgba8 out = picture;
  for (size_t i = 0; i + 3 < out.pixels.size(); i += 4) {
    const unsigned a = picture.pixels[i + 3];
    for (int c = 0; c < 3; ++c)
      out.pixels[i + c] =
          uint8_t((picture.pixels[i + c] * a + background[size_t(c)] * (255 - a) + 127) / 255);
    out.pixels[i + 3] = 255;
  }
  return out;
}

}  // namespace cb
