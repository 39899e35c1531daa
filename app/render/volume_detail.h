// Casting a frame at the volume's detail rather than the screen's. A ray per pixel samples the
// volume more finely than its voxels hold detail once a voxel covers several pixels (the bundled
// 256³ cumulus at 1920×1080: ~2.2 pixels a voxel at its far side from the reference camera, ~4
// from the painter's starting view; at 3840×2160 twice that): the density is trilinear between
// voxels, so neighbouring rays read nearly the same samples. Cast at the scale where each cast
// pixel still covers at most one voxel of the occupied volume's farthest depth and upscaled
// bilinearly, the image is the same to the eye. `bench scale` measured it against a ray per pixel
// at those views (thesis style; physical alike): at half the rays per axis mean 0.03–0.13/255,
// p99 1/255, max 2–6; at a quarter mean 0.06–0.23/255, p99 1, p99.9 ≤ 3, max 10–20 (edge pixels).
// So a frame at rest is cast no coarser than half per axis (kMinStillDetailScale), and a moving
// frame — already at the reduced moving scale — no finer than the volume needs, down to 3/20
// (kMinMovingDetailScale): a coarse volume, such as the half-resolution copy the painter's morph
// and wind play on (~8 pixels a voxel from the painter's starting view at 1920×1080), is cast at
// about a ray a voxel; its wind frames at 0.15 against 0.25 measured mean 0.4/255, p99 1, p99.9
// 2. Only for styles whose pixels are independent of their neighbours
// (RenderStyleRow::reprojects: the screen-space styles' outlines and ink bleeding come out at the
// cast's pixel size) and for skies without texture (none, colour).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "app/scene/camera.h"

namespace cb {

constexpr float kMinStillDetailScale = 0.5f;
constexpr float kMinMovingDetailScale = 0.15f;  // 3/20: the detail's 1/20 steps

// The scale of width and height at which a cast pixel covers at most one voxel (its shortest
// edge) at the farthest view depth of `occupied` — points bounding what can hold density, in
// voxels of a grid whose corner is `world_min` and whose voxels are `voxel` world units (the
// renderer's ray-bounds corners, read in place) — through `camera` on an image `height` pixels
// high: 1 / (pixels a voxel covers there), rounded up to a 1/20 step, within [floor, 1]. 1 when
// `occupied` is empty or lies behind the eye.
float volumeDetailScale(const Camera& camera, int height, const std::vector<glm::vec3>& occupied,
                        glm::vec3 world_min, glm::vec3 voxel, float floor);

// The scale a frame asked at `requested` is cast at, given the volume's detail scale `detail`
// (volumeDetailScale with floor 0): a frame at rest (requested 1) at max(detail,
// kMinStillDetailScale); a moving frame at min(requested, max(detail, kMinMovingDetailScale)).
float detailCastScale(float requested, bool moving, float detail);

}  // namespace cb
