// A rendered frame as the two images a study keeps: `<stem>.exr`, linear light (32-bit float
// RGBA, for compositing and measurement), and `<stem>.png`, the frame as shown (8-bit RGBA).
//
// The ray caster writes its colours straight into a non-sRGB framebuffer that the display shows
// as sRGB, so the frame's values are display-encoded. The EXR holds them decoded with the sRGB
// transfer function (IEC 61966-2-1:1999, §5.2: c ≤ 0.04045 ? c/12.92 : ((c+0.055)/1.055)^2.4;
// negative values clamp to 0); alpha is coverage and is kept as is. The PNG holds the display
// values rounded to 8 bits (clamped to 0..1).
#pragma once

#include <string>
#include <vector>

#include "app/render/image_io.h"

namespace cb {

float srgbToLinear(float encoded);
ImageRgbaF linearFromDisplayEncoded(const ImageRgbaF& display);
ImageRgba8 quantiseDisplay(const ImageRgbaF& display);

// Creates `dir` if needed; returns the paths written (EXR, PNG). Errors name the file.
std::vector<std::string> exportRender(const ImageRgbaF& display_frame, const std::string& dir,
                                      const std::string& stem);

}  // namespace cb
