// An independent CPU evaluation of each render style's formula on single rays, for comparing
// with what the shaders render (render_style_test.cpp). It re-derives everything the GPU does
// from the same inputs — the 8-bit density/transmittance voxels, the camera, the light — with its
// own ray setup, trilinear filtering (clamp to edge, texel centres at i + ½), march and shading,
// written from the seeds' equations rather than from the GLSL.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "app/render/detail_noise.h"
#include "app/render/render_style.h"
#include "app/render/volume_renderer.h"
#include "app/scene/camera.h"
#include "app/scene/light.h"

namespace cb {

struct ReferenceScene {
  glm::ivec3 dims{0};
  glm::vec3 world_min{0.0f}, world_max{0.0f};
  std::vector<uint8_t> voxels;  // RG8 pairs (density, transmittance), x fastest
  Light light;
  Camera camera;
  int width = 0, height = 0;
  RenderOptions options;
  DetailNoise noise;  // the physical style's fBm cube
  // options.sky's LIC layer (makeLicSkyTexture with its settings) when options.sky.kind is lic.
  const std::vector<uint8_t>* sky_lic = nullptr;
};

// Iso-surface constants the renderer uses (volume_renderer.cpp).
inline constexpr float kReferenceIso = 0.3f, kReferenceInnerIso = 0.75f;
inline constexpr float kReferenceInnerDepthFraction = 0.06f;

struct ReferencePixel {
  glm::vec4 rgba{0.0f};  // 0..1, what the pixel should hold
  // A discrete decision (iso hit, band) lies within a hair of its threshold, so the GPU may
  // reasonably take the other side: do not compare this pixel.
  bool ambiguous = false;
  // The pixel lies on a steep ramp of an outline or silhouette (see outlineSensitive): compare
  // it with the looser tolerance.
  bool sensitive = false;
};

// The renderer's 8-bit voxels of `box` as a dense block (what its brick pool holds for them,
// app/render/brick_pool.h): density clamped to [0,1] and the light volume's transmittance, each
// rounded to 8 bits, RG pairs, x fastest; packed holds box.voxelCount() pairs.
void packDensityAndLight(const Volume& volume, const LightVolume& light, const VoxelBox& box,
                         std::vector<uint8_t>* packed);

// The final colour of pixel (x, y), y = 0 at the top, for options.style. For ink and sketch this
// includes the screen-space pass (and, for ink when still, the bleeding over the neighbours).
// What shows behind the cloud is options.background or, when the style shows options.sky, the
// sky (sky_function.h), composited under the cloud with its transmittance. Ink and sketch with
// their sky parameter on are not modelled (their paper is).
ReferencePixel referencePixel(const ReferenceScene& scene, int x, int y);

}  // namespace cb
