// Test helper: per-pixel accumulated opacity of a volume as the real VolumeRenderer draws it
// (alpha of a render over a transparent background), row 0 at the top.
#pragma once

#include <vector>

#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"

namespace cb::test {

std::vector<float> renderedOpacity(VolumeRenderer& renderer, RenderTarget& target,
                                   const Volume& volume, const Camera& camera);

}  // namespace cb::test
