// Renderer defaults from config/render.toml: ray-cast options, background, the resolution scale
// while the camera moves, and the default light.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "app/render/volume_renderer.h"
#include "app/scene/light.h"

namespace cb {

struct RenderConfig {
  RenderOptions options;  // options.scale stays 1 (full resolution when still); .sky, .style_params
  float moving_scale = 0.5f;  // options.scale while the camera moves
  Light light;                // with [light] time_of_day: the sun of that hour (sun_position.h)
  // Problems that fell back to a default, each "FILE:LINE:COL: key what; using …" (also
  // printed on stderr as they are found), and notes such as which of two light settings won.
  std::vector<std::string> warnings;
};

// Reads `path` (see config/render.toml); missing keys keep their defaults. Throws
// std::runtime_error naming the file, the key and the problem for a parse error, a wrong type or
// an out-of-range value of [raycast], [background], [style] name, [motion] and [light]'s
// direction/colour/extinction. The newer settings ([sky], [style.NAME], [light] time_of_day,
// latitude, day_of_year) do not stop the program: a bad value is reported as a warning and its
// default used; a sky image that cannot be read (missing, not a PNG, too large) falls back to
// the sky kind "none".
RenderConfig loadRenderConfig(const std::string& path);
// Every field as render.toml text that the parsers read back (floats with 9 significant digits):
// the render settings in force, as a journal records them.
std::string formatRenderConfig(const RenderConfig& config);
// The same from TOML text in memory (a journal's recorded settings); `name` stands for the file.
RenderConfig parseRenderConfigText(std::string_view text, const std::string& name);

}  // namespace cb
