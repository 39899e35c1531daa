// The sky's colour as a function of the view direction (and, for an image, of the pixel), on the
// CPU: the formula shaders/sky.glsl evaluates per pixel, written out once more for the tests
// and as its documentation. y is up.
//
//   gradient   g = mix(zenith, horizon, (1 − max(dir.y, 0))³) + glow·sun·max(dir·sun, 0)²⁴
//   lic        the far cloud layer (seed 002 §3.2.3, a "sky plane"): the plane y = 1 seen along
//              dir, texture coordinate dir.xz / dir.y · scale (repeating), opacity
//              o = lic(uv) · smoothstep(0.03, 0.3, dir.y) (it fades into the haze at the horizon),
//              colour mix(g, 0.92·sun + 0.08·horizon, 0.85·o)
//   image      the PNG scaled to cover the frame, centred, bilinear
//   cartoon    posterised in its parameters: (1 − dir.y)³ in 5 bands, the glow and the layer's
//              opacity in 3 levels (round(v·n)/n); an image's luminance in 5 levels
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "app/render/image_io.h"
#include "app/render/render_style.h"
#include "app/render/sky_settings.h"

namespace cb {

struct SkyScene {
  SkySettings settings;
  RenderStyle style = RenderStyle::kThesis;
  glm::vec3 sun_dir{0.0f, 1.0f, 0.0f};  // towards the sun, unit
  glm::vec3 sun_colour{1.0f};
  const std::vector<uint8_t>* lic = nullptr;  // makeLicSkyTexture(settings.lic_size, …)
  int frame_width = 1, frame_height = 1;      // the frame the image covers
};

// dir: unit world direction of the pixel's ray; pixel: its centre in pixels, y up from the
// bottom (OpenGL's gl_FragCoord).
glm::vec3 skyColour(const SkyScene& scene, glm::vec3 dir, glm::vec2 pixel);

// The image kind's mapping: image texel coordinates (x right, y down from the top row, texel
// centres at i + ½) shown at `pixel` of a frame_width×frame_height frame.
glm::vec2 skyImageTexel(int image_width, int image_height, int frame_width, int frame_height,
                        glm::vec2 pixel);

// For tests: true when a posterised (cartoon) parameter at dir lies within `margin` of a step,
// where the GPU's filtering may round it the other way.
bool skyNearPosteriseStep(const SkyScene& scene, glm::vec3 dir, float margin);

// The colour the physical style's ambient term takes from the sky: the gradient halfway up.
glm::vec3 skyAmbientColour(const SkySettings& settings);

}  // namespace cb
