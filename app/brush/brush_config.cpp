#include "app/brush/brush_config.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include <toml++/toml.h>

#include "app/core/config_fields.h"
#include "app/core/config_paths.h"
#include "drivers/core/toml_number.h"

namespace cb {
namespace {

std::string where(const std::string& path, const toml::source_region& r) {
  std::ostringstream s;
  s << path << ":" << r.begin.line << ":" << r.begin.column;
  return s.str();
}

class Reader {
 public:
  Reader(const std::string& path, std::vector<std::string>* errors)
      : path_(path), errors_(errors) {}
  bool ok() const { return ok_; }

  void number(const toml::table& t, const char* section, const char* key, float* out, double lo,
              double hi) {
    const toml::node* n = t.get(key);
    if (!n) return;
    // NaN, infinities and values outside lo..hi refused before any conversion.
    std::string why;
    const std::string name = *section ? std::string(section) + "." + key : std::string(key);
    const std::optional<double> v = toml_number::numberIn(*n, path_, name, lo, hi, &why);
    if (!v) {
      errors_->push_back(why);
      ok_ = false;
      return;
    }
    *out = float(*v);
  }
  template <typename Int>
  void integer(const toml::table& t, const char* section, const char* key, Int* out, int64_t lo,
               int64_t hi) {
    const toml::node* n = t.get(key);
    if (!n) return;
    std::optional<int64_t> v = n->value_exact<int64_t>();
    if (!v) return fail(*n, section, key, "expected an integer");
    if (*v < lo || *v > hi) {
      std::ostringstream s;
      s << "must be in [" << lo << ", " << hi << "], got " << *v;
      return fail(*n, section, key, s.str());
    }
    *out = Int(*v);
  }
  void flag(const toml::table& t, const char* section, const char* key, bool* out) {
    const toml::node* n = t.get(key);
    if (!n) return;
    std::optional<bool> v = n->value<bool>();
    if (!v) return fail(*n, section, key, "expected true or false");
    *out = *v;
  }
  void kind(const toml::table& t, const char* key, BrushKind* out) {
    const toml::node* n = t.get(key);
    if (!n) return;
    std::optional<std::string> v = n->value<std::string>();
    if (!v || !parseBrushKind(*v, out))
      fail(*n, "", key, "expected \"2d\", \"3d\" or \"skeleton\"");
  }
  // One row of kBrushFields by its member's type.
  void field(const toml::table& t, const ConfigField<BrushConfig>& f, BrushConfig& c) {
    std::visit(
        [&](auto* member) {
          using T = std::remove_pointer_t<decltype(member)>;
          if constexpr (std::is_same_v<T, float>)
            number(t, f.section, f.key, member, f.lo, f.hi);
          else if constexpr (std::is_same_v<T, bool>)
            flag(t, f.section, f.key, member);
          else if constexpr (std::is_integral_v<T>)
            integer(t, f.section, f.key, member, int64_t(f.lo), int64_t(f.hi));
        },
        f.at(c));
  }
  const toml::table* section(const toml::table& root, const char* name) {
    const toml::node* n = root.get(name);
    if (!n) return nullptr;
    if (!n->is_table()) {
      fail(*n, "", name, "expected a table");
      return nullptr;
    }
    return n->as_table();
  }

 private:
  void fail(const toml::node& n, const char* section, const char* key, const std::string& what) {
    std::string name = *section ? std::string(section) + "." + key : std::string(key);
    errors_->push_back(where(path_, n.source()) + ": " + name + " " + what);
    ok_ = false;
  }
  std::string path_;
  std::vector<std::string>* errors_;
  bool ok_ = true;
};

// Every field of brush.toml but the default brush, in the order the settings text lists them,
// with the range each accepts. stroke.down_pressure / up_pressure are retired: pen contact is the
// calibration's hysteresis alone (calibration profile pressure.contact_down/up). Older brush.toml
// files and journals' Settings records still carry them; they are ignored (the painter never
// used them: its strokes always followed the calibration's contact).
const ConfigField<BrushConfig> kBrushFields[] = {
    {"stroke", "spacing_px", [](BrushConfig& c) -> FieldRef { return &c.stroke.spacing_px; }, 0.25,
     64.0},
    {"stroke", "footprint_scale",
     [](BrushConfig& c) -> FieldRef { return &c.stroke.footprint_scale; }, 0.1, 4.0},
    {"stroke", "size", [](BrushConfig& c) -> FieldRef { return &c.stroke.size; }, kMinBrushSize,
     kMaxBrushSize},
    {"stroke", "billow", [](BrushConfig& c) -> FieldRef { return &c.stroke.billow; }, 0.0, 0.9},
    {"stroke", "billow_length", [](BrushConfig& c) -> FieldRef { return &c.stroke.billow_length; },
     0.25, 16.0},
    {"stroke", "auto_end_still_ms",
     [](BrushConfig& c) -> FieldRef { return &c.stroke.auto_end_still_ms; }, 0, 600000},
    {"stroke", "auto_end_light_ms",
     [](BrushConfig& c) -> FieldRef { return &c.stroke.auto_end_light_ms; }, 0, 600000},
    {"stroke", "auto_end_light_by_hysteresis",
     [](BrushConfig& c) -> FieldRef { return &c.stroke.auto_end_light_by_hysteresis; }},
    {"dispersion", "slow_speed_px_s",
     [](BrushConfig& c) -> FieldRef { return &c.dispersion.slow_speed_px_s; }, 0.0, 1e6},
    {"dispersion", "fast_speed_px_s",
     [](BrushConfig& c) -> FieldRef { return &c.dispersion.fast_speed_px_s; }, 1.0, 1e6},
    {"dispersion", "max_dispersion",
     [](BrushConfig& c) -> FieldRef { return &c.dispersion.max_dispersion; }, 0.0, 1.0},
    {"dispersion", "speed_smoothing_ms",
     [](BrushConfig& c) -> FieldRef { return &c.dispersion.speed_smoothing_ms; }, 0.0, 1000.0},
    {"dispersion", "noise_scale_px",
     [](BrushConfig& c) -> FieldRef { return &c.dispersion.noise_scale_px; }, 1.0, 256.0},
    {"brush2d", "min_diameter_px",
     [](BrushConfig& c) -> FieldRef { return &c.brush2d.min_diameter_px; }, 0.5, 1024.0},
    {"brush2d", "max_diameter_px",
     [](BrushConfig& c) -> FieldRef { return &c.brush2d.max_diameter_px; }, 0.5, 1024.0},
    {"brush2d", "texture_size", [](BrushConfig& c) -> FieldRef { return &c.brush2d.texture_size; },
     8, 1024},
    {"brush2d", "bristles", [](BrushConfig& c) -> FieldRef { return &c.brush2d.bristles; }, 1,
     10000},
    {"brush2d", "texture_seed", [](BrushConfig& c) -> FieldRef { return &c.brush2d.texture_seed; },
     0, 0xffffffffu},
    {"brush3d", "diameter_px", [](BrushConfig& c) -> FieldRef { return &c.brush3d.diameter_px; },
     1.0, 1024.0},
    {"brush3d", "ink_volume_size",
     [](BrushConfig& c) -> FieldRef { return &c.brush3d.ink_volume_size; }, 8, 256},
    {"brush3d", "ink_seed", [](BrushConfig& c) -> FieldRef { return &c.brush3d.ink_seed; }, 0,
     0xffffffffu},
    {"brush3d", "sample_size", [](BrushConfig& c) -> FieldRef { return &c.brush3d.sample_size; }, 8,
     512},
    {"brush3d", "slab_thickness",
     [](BrushConfig& c) -> FieldRef { return &c.brush3d.slab_thickness; }, 0.01, 2.0},
    {"brush3d", "absorption", [](BrushConfig& c) -> FieldRef { return &c.brush3d.absorption; }, 0.0,
     1000.0},
    {"brush3d", "max_tilt_deg", [](BrushConfig& c) -> FieldRef { return &c.brush3d.max_tilt_deg; },
     0.0, 80.0},
    {"brush3d", "pressure_quantum",
     [](BrushConfig& c) -> FieldRef { return &c.brush3d.pressure_quantum; }, 1e-4, 0.25},
    {"brush3d", "tilt_quantum_deg",
     [](BrushConfig& c) -> FieldRef { return &c.brush3d.tilt_quantum_deg; }, 0.01, 15.0},
    {"brush3d", "cache_entries",
     [](BrushConfig& c) -> FieldRef { return &c.brush3d.cache_entries; }, 0, 1 << 20},
    {"skeleton", "segment_length_px",
     [](BrushConfig& c) -> FieldRef { return &c.skeleton.segment_length_px; }, 1.0, 512.0},
    {"skeleton", "time_step_ms",
     [](BrushConfig& c) -> FieldRef { return &c.skeleton.time_step_ms; }, 0.1, 20.0},
    {"skeleton", "constraint_iterations",
     [](BrushConfig& c) -> FieldRef { return &c.skeleton.constraint_iterations; }, 1, 100},
    {"skeleton", "gravity_px_s2",
     [](BrushConfig& c) -> FieldRef { return &c.skeleton.gravity_px_s2; }, 0.0, 1e7},
    {"skeleton", "damping", [](BrushConfig& c) -> FieldRef { return &c.skeleton.damping; }, 0.0,
     1.0},
    {"skeleton", "press_depth", [](BrushConfig& c) -> FieldRef { return &c.skeleton.press_depth; },
     0.0, 1.0},
    {"skeleton", "paper_softness_px",
     [](BrushConfig& c) -> FieldRef { return &c.skeleton.paper_softness_px; }, 0.1, 64.0},
    {"skeleton", "bristles", [](BrushConfig& c) -> FieldRef { return &c.skeleton.bristles; }, 1,
     1000},
    {"skeleton", "bristle_spread_px",
     [](BrushConfig& c) -> FieldRef { return &c.skeleton.bristle_spread_px; }, 0.0, 256.0},
    {"skeleton", "bristle_splay",
     [](BrushConfig& c) -> FieldRef { return &c.skeleton.bristle_splay; }, 0.0, 10.0},
    {"skeleton", "bristle_radius_px",
     [](BrushConfig& c) -> FieldRef { return &c.skeleton.bristle_radius_px; }, 0.1, 32.0},
    {"skeleton", "bristle_points",
     [](BrushConfig& c) -> FieldRef { return &c.skeleton.bristle_points; }, 2, 256},
    {"skeleton", "max_steps_per_sample",
     [](BrushConfig& c) -> FieldRef { return &c.skeleton.max_steps_per_sample; }, 1, 100000},
    {"skeleton", "stamp_spacing_px",
     [](BrushConfig& c) -> FieldRef { return &c.skeleton.stamp_spacing_px; }, 0.0, 64.0},
    {"skeleton", "end_settle_steps",
     [](BrushConfig& c) -> FieldRef { return &c.skeleton.end_settle_steps; }, 0, 10000},
    {"skeleton", "seed", [](BrushConfig& c) -> FieldRef { return &c.skeleton.seed; }, 0,
     0xffffffffu},
};

}  // namespace

const char* brushKindName(BrushKind kind) {
  switch (kind) {
    case BrushKind::k2D:
      return "2d";
    case BrushKind::k3D:
      return "3d";
    case BrushKind::kSkeleton:
      return "skeleton";
  }
  return "?";
}

bool parseBrushKind(const std::string& name, BrushKind* kind) {
  if (name == "2d")
    *kind = BrushKind::k2D;
  else if (name == "3d")
    *kind = BrushKind::k3D;
  else if (name == "skeleton")
    *kind = BrushKind::kSkeleton;
  else
    return false;
  return true;
}

namespace {
bool brushConfigFrom(const toml::table& root, const std::string& path, BrushConfig* c,
                     std::vector<std::string>* errors);
}  // namespace

bool loadBrushConfig(const std::string& path, BrushConfig* c, std::vector<std::string>* errors) {
  toml::table root;
  try {
    root = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    errors->push_back(where(path, e.source()) + ": " + std::string(e.description()));
    return false;
  }
  return brushConfigFrom(root, path, c, errors);
}

bool parseBrushConfigText(std::string_view text, const std::string& name, BrushConfig* c,
                          std::vector<std::string>* errors) {
  toml::table root;
  try {
    root = toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    errors->push_back(where(name, e.source()) + ": " + std::string(e.description()));
    return false;
  }
  return brushConfigFrom(root, name, c, errors);
}

namespace {
bool brushConfigFrom(const toml::table& root, const std::string& path, BrushConfig* c,
                     std::vector<std::string>* errors) {
  Reader r(path, errors);
  r.kind(root, "brush", &c->default_brush);
  const char* open = nullptr;
  const toml::table* t = nullptr;
  for (const ConfigField<BrushConfig>& f : kBrushFields) {
    if (!open || std::string_view(open) != f.section) t = r.section(root, open = f.section);
    if (t) r.field(*t, f, *c);
  }
  if (c->brush2d.max_diameter_px < c->brush2d.min_diameter_px) {
    errors->push_back(path + ": brush2d.max_diameter_px is below min_diameter_px; both reset");
    c->brush2d.min_diameter_px = Brush2DParams{}.min_diameter_px;
    c->brush2d.max_diameter_px = Brush2DParams{}.max_diameter_px;
    return false;
  }
  return r.ok();
}
}  // namespace

float steppedBrushSize(float size, int steps) {
  return std::clamp(size * std::pow(kBrushSizeStep, float(steps)), kMinBrushSize, kMaxBrushSize);
}

std::string formatBrushConfig(const BrushConfig& c) {
  std::string o = std::string("brush = \"") + brushKindName(c.default_brush) + "\"\n";
  appendSections<BrushConfig>(o, kBrushFields, c);
  return o;
}

BrushConfig loadDefaultBrushConfig() {
  BrushConfig config;
  std::vector<std::string> errors;
  if (!loadBrushConfig(configFile("brush.toml"), &config, &errors))
    for (const std::string& e : errors)
      std::fprintf(stderr, "cloudbrush: %s (using the default)\n", e.c_str());
  return config;
}

}  // namespace cb
