// Fine speckle in a rendered image: small islands of dark pixels inside a cloud — the dots and
// broken dashes a noisy iso-surface, normal or threshold leaves in the line-drawn styles — as
// opposed to the lines a style means to draw (an outline, an inner silhouette), which are long
// connected runs of dark pixels.
#pragma once

#include "app/render/image_io.h"

namespace cb::test {

struct Speckle {
  long cloud = 0;    // pixels that differ from the empty sky's image
  long dark = 0;     // of those, darker than the style's fill tones (its lines)
  long speckle = 0;  // of those, in 8-connected dark islands of at most max_island pixels
  long islands = 0;  // 8-connected dark islands of any size
  double fraction() const { return cloud ? double(speckle) / double(cloud) : 0.0; }
};

// A pixel's luminance (0..1, Rec. 709) from its 8-bit RGB.
float pixelLuminance(const uint8_t* p);
// A pixel of the image that differs from the empty sky's: by more than 12 of 765 summed levels,
// above the renderer's rounding and below any painted tone.
bool differsFromEmpty(const uint8_t* p, const uint8_t* empty);

// `image` and `empty` (the same view without the cloud) of equal size; `dark_luminance` the
// luminance (0..1, Rec. 709) below which a cloud pixel is line ink, not a fill tone.
Speckle measureSpeckle(const ImageRgba8& image, const ImageRgba8& empty, float dark_luminance,
                       int max_island);

}  // namespace cb::test
