#include "app/mapping/mapping_config.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include <toml++/toml.h>

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
  std::string o;
  char buf[64];
  const auto num = [&](const char* key, double v) {
    std::snprintf(buf, sizeof buf, "%.9g", v);
    o += std::string(key) + " = " + buf + "\n";
  };
  const auto integer = [&](const char* key, long long v) {
    o += std::string(key) + " = " + std::to_string(v) + "\n";
  };
  const auto flag = [&](const char* key, bool v) {
    o += std::string(key) + " = " + (v ? "true" : "false") + "\n";
  };
  o += std::string("[mapping]\nmethod = \"") + toString(c.method) + "\"\n\n[circles]\n";
  integer("initial_diameter_px", c.circles.initial_diameter_px);
  integer("min_radius_px", c.circles.min_radius_px);
  integer("directions", c.circles.directions);
  num("accept_white_ratio", c.circles.accept_white_ratio);
  num("drop_empty_ratio", c.circles.drop_empty_ratio);
  num("white_threshold", c.circles.white_threshold);
  num("empty_threshold", c.circles.empty_threshold);
  flag("white_relative_to_peak", c.circles.white_relative_to_peak);
  flag("reseed_along_path", c.circles.reseed_along_path);
  flag("empty_test_on_smallest", c.circles.empty_test_on_smallest);
  o += "\n[spheres]\n";
  num("density", c.spheres.density);
  num("edge_softness", c.spheres.edge_softness);
  num("noise_erosion", c.spheres.noise_erosion);
  num("noise_modulation", c.spheres.noise_modulation);
  num("outline_chord_voxels", c.spheres.outline_chord_voxels);
  num("billow_amplitude", c.spheres.billow_amplitude);
  num("billow_feature_radii", c.spheres.billow_feature_radii);
  num("puff_probability", c.spheres.puff_probability);
  o += "\n[edges]\n";
  integer("samples_per_pixel", c.edges.samples_per_pixel);
  num("depth_sigma_of_radius", c.edges.depth_sigma_of_radius);
  num("lateral_sigma_px", c.edges.lateral_sigma_px);
  num("min_depth_sigma_voxels", c.edges.min_depth_sigma_voxels);
  num("density_scale", c.edges.density_scale);
  flag("tangent_at_sphere_depth", c.edges.tangent_at_sphere_depth);
  o += "\n[ray_marching]\n";
  num("density", c.ray_marching.density);
  o += "\n[sheet]\n";
  num("sigma_voxels", c.sheet.sigma_voxels);
  num("erosion", c.sheet.erosion);
  o += "\n[noise]\n";
  integer("seed", c.noise.seed);
  integer("size", c.noise.size);
  num("period_voxels", c.noise.period_voxels);
  integer("octaves", c.noise.octaves);
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
  read(root, path, "circles", "initial_diameter_px", &c.circles.initial_diameter_px);
  read(root, path, "circles", "min_radius_px", &c.circles.min_radius_px);
  read(root, path, "circles", "directions", &c.circles.directions);
  read(root, path, "circles", "accept_white_ratio", &c.circles.accept_white_ratio);
  read(root, path, "circles", "drop_empty_ratio", &c.circles.drop_empty_ratio);
  read(root, path, "circles", "white_threshold", &c.circles.white_threshold);
  read(root, path, "circles", "empty_threshold", &c.circles.empty_threshold);
  read(root, path, "circles", "white_relative_to_peak", &c.circles.white_relative_to_peak);
  read(root, path, "circles", "reseed_along_path", &c.circles.reseed_along_path);
  read(root, path, "circles", "empty_test_on_smallest", &c.circles.empty_test_on_smallest);
  read(root, path, "spheres", "density", &c.spheres.density);
  read(root, path, "spheres", "edge_softness", &c.spheres.edge_softness);
  read(root, path, "spheres", "noise_erosion", &c.spheres.noise_erosion);
  read(root, path, "spheres", "noise_modulation", &c.spheres.noise_modulation);
  read(root, path, "spheres", "outline_chord_voxels", &c.spheres.outline_chord_voxels);
  read(root, path, "spheres", "billow_amplitude", &c.spheres.billow_amplitude);
  read(root, path, "spheres", "billow_feature_radii", &c.spheres.billow_feature_radii);
  read(root, path, "spheres", "puff_probability", &c.spheres.puff_probability);
  read(root, path, "edges", "samples_per_pixel", &c.edges.samples_per_pixel);
  read(root, path, "edges", "depth_sigma_of_radius", &c.edges.depth_sigma_of_radius);
  read(root, path, "edges", "lateral_sigma_px", &c.edges.lateral_sigma_px);
  read(root, path, "edges", "tangent_at_sphere_depth", &c.edges.tangent_at_sphere_depth);
  read(root, path, "edges", "min_depth_sigma_voxels", &c.edges.min_depth_sigma_voxels);
  read(root, path, "edges", "density_scale", &c.edges.density_scale);
  read(root, path, "ray_marching", "density", &c.ray_marching.density);
  read(root, path, "sheet", "sigma_voxels", &c.sheet.sigma_voxels);
  read(root, path, "sheet", "erosion", &c.sheet.erosion);
  read(root, path, "noise", "seed", &c.noise.seed);
  read(root, path, "noise", "size", &c.noise.size);
  read(root, path, "noise", "period_voxels", &c.noise.period_voxels);
  read(root, path, "noise", "octaves", &c.noise.octaves);
  try {
    validate(c);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
  return c;
}
}  // namespace

}  // namespace cb
