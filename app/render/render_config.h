// Renderer defaults from config/render.toml: ray-cast options, background, the resolution scale
// while the camera moves, and the default light.
#pragma once

#include <string>

#include "app/render/volume_renderer.h"
#include "app/scene/light.h"

namespace cb {

struct RenderConfig {
  RenderOptions options;      // options.scale stays 1 (full resolution when still)
  float moving_scale = 0.5f;  // options.scale while the camera moves
  Light light;
};

// Reads `path` (see config/render.toml); missing keys keep their defaults. Throws
// std::runtime_error naming the file, the key and the problem for a parse error, a wrong type or
// an out-of-range value.
RenderConfig loadRenderConfig(const std::string& path);

}  // namespace cb
