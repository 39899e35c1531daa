// A task's reference picture as the participant sees it. A picture may carry its shape in the
// alpha channel only (the bundled duck toy: a silhouette for picture → cloud, its colour one
// flat grey); shown by copying RGB it is a blank box. It is shown composited over a light
// background (out = a·rgb + (1 − a)·background), as any image viewer shows it.
#pragma once

#include <array>
#include <cstdint>

#include "app/render/image_io.h"

namespace cb {

// The background behind a reference picture: white paper.
inline constexpr std::array<uint8_t, 3> kReferencePictureBackground = {255, 255, 255};

// `picture` composited over `background`, alpha 255 everywhere.
ImageRgba8 referencePictureForDisplay(
    const ImageRgba8& picture,
    const std::array<uint8_t, 3>& background = kReferencePictureBackground);

}  // namespace cb
