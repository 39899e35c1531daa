#include "app/render/render_config.h"

#include <cstdio>
#include <stdexcept>

#include <toml++/toml.h>

#include "app/core/toml_file.h"

namespace cb {
namespace {

[[noreturn]] void bad(const std::string& path, const std::string& key, const std::string& what) {
  throw std::runtime_error(path + ": " + key + " " + what);
}

template <class T>
void read(const toml::table& root, const std::string& path, const char* section, const char* key,
          T* out) {
  auto node = root[section][key];
  if (!node) return;
  if constexpr (std::is_same_v<T, bool>) {
    auto v = node.template value<bool>();
    if (!v) bad(path, std::string(section) + "." + key, "must be true or false");
    *out = *v;
  } else {
    auto v = node.template value<double>();
    if (!v) bad(path, std::string(section) + "." + key, "must be a number");
    *out = T(*v);
  }
}

// True when the key was present (and read).
template <int N>
bool readVec(const toml::table& root, const std::string& path, const char* section, const char* key,
             glm::vec<N, float>* out) {
  auto node = root[section][key];
  if (!node) return false;
  const toml::array* a = node.as_array();
  const std::string name = std::string(section) + "." + key;
  if (!a || a->size() != size_t(N))
    bad(path, name, "must be an array of " + std::to_string(N) + " numbers");
  for (int i = 0; i < N; ++i) {
    auto v = (*a)[size_t(i)].template value<double>();
    if (!v) bad(path, name, "must be an array of numbers");
    (*out)[i] = float(*v);
  }
  return true;
}

}  // namespace

namespace {
RenderConfig renderConfigFrom(const toml::table& root, const std::string& path);
}  // namespace

std::string formatRenderConfig(const RenderConfig& c) {
  std::string o;
  char buf[64];
  const auto num = [&](const char* key, double v) {
    std::snprintf(buf, sizeof buf, "%.9g", v);
    o += std::string(key) + " = " + buf + "\n";
  };
  const auto vec = [&](const char* key, const float* v, int n) {
    o += std::string(key) + " = [";
    for (int i = 0; i < n; ++i) {
      std::snprintf(buf, sizeof buf, "%s%.9g", i ? ", " : "", double(v[i]));
      o += buf;
    }
    o += "]\n";
  };
  const RenderOptions& r = c.options;
  o += "[raycast]\n";
  num("step_voxels", r.step_voxels);
  num("extinction_per_voxel", r.extinction_per_voxel);
  num("termination_transmittance", r.termination_transmittance);
  o += std::string("skip_empty_space = ") + (r.skip_empty_space ? "true" : "false") + "\n";
  o += std::string("brick_stepping = ") + (r.brick_stepping ? "true" : "false") + "\n";
  o += "\n[background]\n";
  vec("colour", &r.background.x, 4);
  o += std::string("\n[style]\nname = \"") + renderStyleName(r.style) + "\"\n\n[motion]\n";
  num("moving_scale", c.moving_scale);
  o += "\n[light]\n";
  vec("direction", &c.light.direction.x, 3);
  vec("colour", &c.light.colour.x, 3);
  num("extinction", c.light.extinction);
  return o;
}

RenderConfig loadRenderConfig(const std::string& path) {
  return renderConfigFrom(parseTomlFileOrThrow(path), path);
}

RenderConfig parseRenderConfigText(std::string_view text, const std::string& name) {
  return renderConfigFrom(parseTomlTextOrThrow(text, name), name);
}

namespace {
RenderConfig renderConfigFrom(const toml::table& root, const std::string& path) {
  RenderConfig c;
  RenderOptions& o = c.options;
  read(root, path, "raycast", "step_voxels", &o.step_voxels);
  read(root, path, "raycast", "extinction_per_voxel", &o.extinction_per_voxel);
  read(root, path, "raycast", "termination_transmittance", &o.termination_transmittance);
  read(root, path, "raycast", "skip_empty_space", &o.skip_empty_space);
  read(root, path, "raycast", "brick_stepping", &o.brick_stepping);
  readVec<4>(root, path, "background", "colour", &o.background);
  if (auto node = root["style"]["name"]) {
    auto name = node.value<std::string>();
    auto style = name ? parseRenderStyle(*name) : std::nullopt;
    if (!style) bad(path, "style.name", "must be one of " + renderStyleNameList());
    o.style = *style;
  }
  read(root, path, "motion", "moving_scale", &c.moving_scale);
  // light.direction points towards the sun; the older light.position (a light ball seen from
  // the origin) gives the same direction.
  glm::vec3 towards(0.0f);
  if (readVec<3>(root, path, "light", "position", &towards) && glm::length(towards) > 0.0f)
    c.light.direction = Light::directionTowards(towards);
  if (readVec<3>(root, path, "light", "direction", &towards) && glm::length(towards) > 0.0f)
    c.light.direction = Light::directionTowards(towards);
  readVec<3>(root, path, "light", "colour", &c.light.colour);
  read(root, path, "light", "extinction", &c.light.extinction);
  if (!(o.step_voxels >= 0.1f && o.step_voxels <= 8.0f))
    bad(path, "raycast.step_voxels", "must be in [0.1, 8]");
  if (!(o.extinction_per_voxel > 0.0f)) bad(path, "raycast.extinction_per_voxel", "must be > 0");
  if (!(o.termination_transmittance >= 0.0f && o.termination_transmittance < 1.0f))
    bad(path, "raycast.termination_transmittance", "must be in [0, 1)");
  if (!(c.moving_scale >= 0.05f && c.moving_scale <= 1.0f))
    bad(path, "motion.moving_scale", "must be in [0.05, 1]");
  if (!(c.light.extinction >= 0.0f && c.light.extinction <= 1.0f))
    bad(path, "light.extinction", "must be in [0, 1]");
  return c;
}
}  // namespace

}  // namespace cb
