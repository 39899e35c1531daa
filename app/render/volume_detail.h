// Casting a still frame at the volume's detail rather than the screen's. A ray per pixel samples
// the volume more finely than its voxels hold detail once a voxel covers several pixels (the
// bundled 256³ cumulus at 1920×1080 from the reference camera: ~2.5 pixels a voxel; at
// 3840×2160 twice that): the density is trilinear between voxels, so neighbouring rays read
// nearly the same samples. Cast at the scale where each cast pixel still covers at most one
// voxel of the occupied volume's farthest depth and upscaled bilinearly (as a moving frame is,
// but at the still frame's step), the image is the same to the eye: `bench scale` measured it
// against every pixel cast at mean 0.03–0.13/255, p99 1/255 for the thesis and physical styles at
// the reference and painter's views, 1920×1080 and 3840×2160, for a third of the time.
// Only for styles whose pixels are independent of their neighbours (RenderStyleRow::reprojects:
// the screen-space styles' outlines and ink bleeding come out at the cast's pixel size) and for
// skies without texture (none, colour).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "app/scene/camera.h"

namespace cb {

// Never cast coarser than this (measured down to it; see above).
constexpr float kMinDetailScale = 0.5f;

// The scale of width and height at which a cast pixel covers at most one voxel (edge `voxel`
// world units) at the farthest view depth of `occupied` (world points bounding what can hold
// density), through `camera` on an image `height` pixels high: 1 / (pixels a voxel covers
// there), rounded up to a 1/20 step, within [kMinDetailScale, 1]. 1 when `occupied` is empty or
// lies behind the eye.
float volumeDetailScale(const Camera& camera, int height, const std::vector<glm::vec3>& occupied,
                        float voxel);

}  // namespace cb
