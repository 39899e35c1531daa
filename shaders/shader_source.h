// Shaders are GLSL files in shaders/, embedded into the binary at build time.
#pragma once

#include <string_view>

namespace cb {
// The text of shaders/<name> (e.g. "raycast.frag.glsl"); empty if there is no such shader.
std::string_view shaderSource(std::string_view name);
}  // namespace cb
