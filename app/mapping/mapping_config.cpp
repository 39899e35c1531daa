#include "app/mapping/mapping_config.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include <toml++/toml.h>

#include "app/core/config_fields.h"
#include "app/core/toml_file.h"
#include "drivers/core/toml_number.h"

namespace cb {
namespace {

// Reads table.key into *out if present; throws naming file and key on a wrong type.
template <typename T>
void read(const toml::table& root, const std::string& file, const char* table, const char* key,
          T* out) {
  const toml::node* node = root.at_path(std::string(table) + "." + key).node();
  if (!node) return;
  if constexpr (std::is_same_v<T, bool>) {
    if (auto v = node->value<bool>()) {
      *out = *v;
      return;
    }
  } else if constexpr (std::is_integral_v<T>) {
    // Through toml_number: value<int64_t>() would convert a float before checking its range.
    std::string why;
    const auto v = toml_number::integerIn(
        *node, file, std::string(table) + "." + key, int64_t(std::numeric_limits<T>::min()),
        int64_t(std::min<uint64_t>(std::numeric_limits<T>::max(), INT64_MAX)), &why);
    if (!v) throw std::runtime_error(why);
    *out = T(*v);
    return;
  } else {
    std::string why;
    const auto v = toml_number::numberIn(*node, file, std::string(table) + "." + key,
                                         -std::numeric_limits<double>::max(),
                                         std::numeric_limits<double>::max(), &why);
    if (!v) throw std::runtime_error(why);
    *out = T(*v);
    return;
  }
  throw std::runtime_error(file + ": " + table + "." + key + " has the wrong type");
}

// Every field of mapping.toml but [mapping] method, in the order the settings text lists them
// (the ranges are validate()'s).
const ConfigField<MappingConfig> kMappingFields[] = {
    {"circles", "initial_diameter_px",
     [](MappingConfig& c) -> FieldRef { return &c.circles.initial_diameter_px; }},
    {"circles", "min_radius_px",
     [](MappingConfig& c) -> FieldRef { return &c.circles.min_radius_px; }},
    {"circles", "directions", [](MappingConfig& c) -> FieldRef { return &c.circles.directions; }},
    {"circles", "accept_white_ratio",
     [](MappingConfig& c) -> FieldRef { return &c.circles.accept_white_ratio; }},
    {"circles", "drop_empty_ratio",
     [](MappingConfig& c) -> FieldRef { return &c.circles.drop_empty_ratio; }},
    {"circles", "white_threshold",
     [](MappingConfig& c) -> FieldRef { return &c.circles.white_threshold; }},
    {"circles", "empty_threshold",
     [](MappingConfig& c) -> FieldRef { return &c.circles.empty_threshold; }},
    {"circles", "white_relative_to_peak",
     [](MappingConfig& c) -> FieldRef { return &c.circles.white_relative_to_peak; }},
    {"circles", "reseed_along_path",
     [](MappingConfig& c) -> FieldRef { return &c.circles.reseed_along_path; }},
    {"circles", "empty_test_on_smallest",
     [](MappingConfig& c) -> FieldRef { return &c.circles.empty_test_on_smallest; }},
    {"spheres", "density", [](MappingConfig& c) -> FieldRef { return &c.spheres.density; }},
    {"spheres", "edge_softness",
     [](MappingConfig& c) -> FieldRef { return &c.spheres.edge_softness; }},
    {"spheres", "noise_erosion",
     [](MappingConfig& c) -> FieldRef { return &c.spheres.noise_erosion; }},
    {"spheres", "noise_modulation",
     [](MappingConfig& c) -> FieldRef { return &c.spheres.noise_modulation; }},
    {"spheres", "outline_chord_voxels",
     [](MappingConfig& c) -> FieldRef { return &c.spheres.outline_chord_voxels; }},
    {"spheres", "billow_amplitude",
     [](MappingConfig& c) -> FieldRef { return &c.spheres.billow_amplitude; }},
    {"spheres", "billow_feature_radii",
     [](MappingConfig& c) -> FieldRef { return &c.spheres.billow_feature_radii; }},
    {"spheres", "puff_probability",
     [](MappingConfig& c) -> FieldRef { return &c.spheres.puff_probability; }},
    {"edges", "samples_per_pixel",
     [](MappingConfig& c) -> FieldRef { return &c.edges.samples_per_pixel; }},
    {"edges", "depth_sigma_of_radius",
     [](MappingConfig& c) -> FieldRef { return &c.edges.depth_sigma_of_radius; }},
    {"edges", "lateral_sigma_px",
     [](MappingConfig& c) -> FieldRef { return &c.edges.lateral_sigma_px; }},
    {"edges", "min_depth_sigma_voxels",
     [](MappingConfig& c) -> FieldRef { return &c.edges.min_depth_sigma_voxels; }},
    {"edges", "density_scale", [](MappingConfig& c) -> FieldRef { return &c.edges.density_scale; }},
    {"edges", "tangent_at_sphere_depth",
     [](MappingConfig& c) -> FieldRef { return &c.edges.tangent_at_sphere_depth; }},
    {"ray_marching", "density",
     [](MappingConfig& c) -> FieldRef { return &c.ray_marching.density; }},
    {"sheet", "sigma_voxels", [](MappingConfig& c) -> FieldRef { return &c.sheet.sigma_voxels; }},
    {"sheet", "erosion", [](MappingConfig& c) -> FieldRef { return &c.sheet.erosion; }},
    {"noise", "seed", [](MappingConfig& c) -> FieldRef { return &c.noise.seed; }},
    {"noise", "size", [](MappingConfig& c) -> FieldRef { return &c.noise.size; }},
    {"noise", "period_voxels", [](MappingConfig& c) -> FieldRef { return &c.noise.period_voxels; }},
    {"noise", "octaves", [](MappingConfig& c) -> FieldRef { return &c.noise.octaves; }},
};

void require(bool ok, const char* field, const char* rule) {
  if (!ok) throw std::invalid_argument(std::string("mapping config: ") + field + " " + rule);
}

}  // namespace

const char* toString(MappingMethod method) {
  switch (method) {
    case MappingMethod::kHybrid:
      return "hybrid";
    case MappingMethod::kRayMarching:
      return "ray-marching";
    case MappingMethod::kSheet:
      return "sheet";
  }
  return "?";
}

bool parseMappingMethod(const std::string& text, MappingMethod* method) {
  if (text == "hybrid" || text == "hmm") {
    *method = MappingMethod::kHybrid;
    return true;
  }
  if (text == "ray-marching" || text == "rmm") {
    *method = MappingMethod::kRayMarching;
    return true;
  }
  if (text == "sheet") {
    *method = MappingMethod::kSheet;
    return true;
  }
  return false;
}

void validate(const MappingConfig& c) {
  require(c.circles.initial_diameter_px >= 2 && c.circles.initial_diameter_px <= 4096,
          "circles.initial_diameter_px", "must be in 2..4096");
  require(
      c.circles.min_radius_px >= 1 && c.circles.min_radius_px <= c.circles.initial_diameter_px / 2,
      "circles.min_radius_px", "must be in 1..initial_diameter_px/2");
  require(c.circles.directions >= 1 && c.circles.directions <= 64, "circles.directions",
          "must be in 1..64");
  require(c.circles.accept_white_ratio > 0.0f && c.circles.accept_white_ratio <= 1.0f,
          "circles.accept_white_ratio", "must be in (0,1]");
  require(c.circles.drop_empty_ratio >= 0.0f && c.circles.drop_empty_ratio <= 1.0f,
          "circles.drop_empty_ratio", "must be in [0,1]");
  require(c.circles.empty_threshold >= 0.0f &&
              c.circles.empty_threshold < c.circles.white_threshold &&
              c.circles.white_threshold <= 1.0f,
          "circles.white_threshold/empty_threshold", "must satisfy 0 <= empty < white <= 1");
  require(c.spheres.density > 0.0f, "spheres.density", "must be > 0");
  require(c.spheres.edge_softness > 0.0f && c.spheres.edge_softness <= 1.0f,
          "spheres.edge_softness", "must be in (0,1]");
  require(c.spheres.noise_erosion >= 0.0f && c.spheres.noise_erosion < 1.0f,
          "spheres.noise_erosion", "must be in [0,1)");
  require(c.spheres.noise_modulation >= 0.0f && c.spheres.noise_modulation <= 1.0f,
          "spheres.noise_modulation", "must be in [0,1]");
  require(c.spheres.outline_chord_voxels >= 0.0f && c.spheres.outline_chord_voxels <= 64.0f,
          "spheres.outline_chord_voxels", "must be in [0, 64]");
  require(c.spheres.billow_amplitude >= 0.0f && c.spheres.billow_amplitude <= 2.0f,
          "spheres.billow_amplitude", "must be in [0, 2]");
  require(c.spheres.puff_probability >= 0.0f && c.spheres.puff_probability <= 1.0f,
          "spheres.puff_probability", "must be in [0, 1]");
  require(c.spheres.billow_feature_radii > 0.0f && c.spheres.billow_feature_radii <= 64.0f,
          "spheres.billow_feature_radii", "must be in (0, 64]");
  require(c.edges.samples_per_pixel >= 1 && c.edges.samples_per_pixel <= 64,
          "edges.samples_per_pixel", "must be in 1..64");
  require(c.edges.depth_sigma_of_radius >= 0.0f, "edges.depth_sigma_of_radius", "must be >= 0");
  require(c.edges.min_depth_sigma_voxels >= 0.0f, "edges.min_depth_sigma_voxels", "must be >= 0");
  require(c.edges.lateral_sigma_px >= 0.0f, "edges.lateral_sigma_px", "must be >= 0");
  require(c.edges.density_scale > 0.0f, "edges.density_scale", "must be > 0");
  require(c.ray_marching.density > 0.0f, "ray_marching.density", "must be > 0");
  require(c.sheet.sigma_voxels >= 0.25f && c.sheet.sigma_voxels <= 64.0f, "sheet.sigma_voxels",
          "must be in [0.25, 64]");
  require(c.sheet.erosion >= 0.0f && c.sheet.erosion <= 1.0f, "sheet.erosion", "must be in [0, 1]");
  require(c.noise.size >= 8 && c.noise.size <= 256 && (c.noise.size & (c.noise.size - 1)) == 0,
          "noise.size", "must be a power of two in 8..256");
  require(c.noise.period_voxels >= 2.0f, "noise.period_voxels", "must be >= 2");
  require(c.noise.octaves >= 1 && c.noise.octaves <= 8, "noise.octaves", "must be in 1..8");
}

namespace {
MappingConfig mappingConfigFrom(const toml::table& root, const std::string& path, MappingConfig c);
}  // namespace

std::string formatMappingConfig(const MappingConfig& c) {
  std::string o = std::string("[mapping]\nmethod = \"") + toString(c.method) + "\"\n";
  appendSections<MappingConfig>(o, kMappingFields, c);
  return o;
}

MappingConfig loadMappingConfig(const std::string& path) {
  return mappingConfigFrom(parseTomlFileOrThrow(path), path, MappingConfig{});
}

MappingConfig parseMappingConfigText(std::string_view text, const std::string& name,
                                     const MappingConfig& absent) {
  return mappingConfigFrom(parseTomlTextOrThrow(text, name), name, absent);
}

namespace {
MappingConfig mappingConfigFrom(const toml::table& root, const std::string& path, MappingConfig c) {
  if (auto m = root["mapping"]["method"].value<std::string>()) {
    if (!parseMappingMethod(*m, &c.method))
      throw std::runtime_error(path + ": mapping.method '" + *m +
                               "' is not one of hybrid, ray-marching, sheet");
  }
  for (const ConfigField<MappingConfig>& f : kMappingFields)
    std::visit([&](auto* member) { read(root, path, f.section, f.key, member); }, f.at(c));
  try {
    validate(c);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
  return c;
}
}  // namespace

}  // namespace cb
