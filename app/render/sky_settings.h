// The sky behind the clouds (config/render.toml [sky]): none (the flat [background] colour, as
// before), a zenith-to-horizon colour gradient, that gradient with a far cloud layer made by
// line-integral convolution (seed 002, Yu & Wang §3.2.3 "LIC cloudy sky plane"), or a loaded
// PNG behind the frame. The cloud is composited over it with its transmittance (premultiplied
// "over": C = C_cloud + T·C_sky). Each render style decides how the sky looks with it
// (sky_function.h): the paper styles keep their paper unless [style.ink]/[style.sketch] sky =
// true, the cartoon posterises it.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "app/render/image_io.h"

namespace cb {

enum class SkyKind { kNone, kColour, kLic, kImage };

// "none", "colour", "lic", "image" (config), and back.
const char* skyKindName(SkyKind kind);
bool parseSkyKind(const std::string& name, SkyKind* kind);

struct SkySettings {
  SkyKind kind = SkyKind::kNone;
  glm::vec3 zenith{0.26f, 0.45f, 0.78f};   // straight up
  glm::vec3 horizon{0.70f, 0.80f, 0.91f};  // at and below the horizon
  float sun_glow = 0.35f;                  // halo around the sun, times the sun's colour
  // LIC cloud layer (sky_lic.h): texture seed and size, streak half length in texels, how much
  // of the layer is cloud (0..1) and the layer's scale (texture repeats per unit of the ray's
  // horizontal run over its rise: larger = smaller distant clouds).
  uint32_t lic_seed = 2014;
  int lic_size = 512;
  int lic_length = 24;
  float lic_coverage = 0.5f;
  float lic_scale = 0.35f;
  // Image (kind image): decoded once when the config is read, shown behind the frame scaled to
  // cover it (centred, aspect kept).
  std::string image_path;
  std::shared_ptr<const ImageRgba8> image;
};

// Images larger than this are refused before decoding (8192×8192).
inline constexpr int64_t kMaxSkyImagePixels = int64_t(8192) * 8192;

}  // namespace cb
