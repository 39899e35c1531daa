#include "app/brush/brush_config.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include <toml++/toml.h>

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
  if (const toml::table* t = r.section(root, "stroke")) {
    // stroke.down_pressure / up_pressure are retired: pen contact is the calibration's
    // hysteresis alone (calibration profile pressure.contact_down/up). Older brush.toml files
    // and journals' Settings records still carry them; they are ignored (the painter never
    // used them: its strokes always followed the calibration's contact).
    r.number(*t, "stroke", "spacing_px", &c->stroke.spacing_px, 0.25, 64.0);
    r.number(*t, "stroke", "footprint_scale", &c->stroke.footprint_scale, 0.1, 4.0);
    r.number(*t, "stroke", "size", &c->stroke.size, kMinBrushSize, kMaxBrushSize);
    r.number(*t, "stroke", "billow", &c->stroke.billow, 0.0, 0.9);
    r.number(*t, "stroke", "billow_length", &c->stroke.billow_length, 0.25, 16.0);
    r.integer(*t, "stroke", "auto_end_still_ms", &c->stroke.auto_end_still_ms, 0, 600000);
    r.integer(*t, "stroke", "auto_end_light_ms", &c->stroke.auto_end_light_ms, 0, 600000);
    r.flag(*t, "stroke", "auto_end_light_by_hysteresis", &c->stroke.auto_end_light_by_hysteresis);
  }
  if (const toml::table* t = r.section(root, "dispersion")) {
    DispersionParams& d = c->dispersion;
    r.number(*t, "dispersion", "slow_speed_px_s", &d.slow_speed_px_s, 0.0, 1e6);
    r.number(*t, "dispersion", "fast_speed_px_s", &d.fast_speed_px_s, 1.0, 1e6);
    r.number(*t, "dispersion", "max_dispersion", &d.max_dispersion, 0.0, 1.0);
    r.number(*t, "dispersion", "speed_smoothing_ms", &d.speed_smoothing_ms, 0.0, 1000.0);
    r.number(*t, "dispersion", "noise_scale_px", &d.noise_scale_px, 1.0, 256.0);
  }
  if (const toml::table* t = r.section(root, "brush2d")) {
    Brush2DParams& b = c->brush2d;
    r.number(*t, "brush2d", "min_diameter_px", &b.min_diameter_px, 0.5, 1024.0);
    r.number(*t, "brush2d", "max_diameter_px", &b.max_diameter_px, 0.5, 1024.0);
    r.integer(*t, "brush2d", "texture_size", &b.texture_size, 8, 1024);
    r.integer(*t, "brush2d", "bristles", &b.bristles, 1, 10000);
    r.integer(*t, "brush2d", "texture_seed", &b.texture_seed, 0, 0xffffffffll);
  }
  if (const toml::table* t = r.section(root, "brush3d")) {
    Brush3DParams& b = c->brush3d;
    r.number(*t, "brush3d", "diameter_px", &b.diameter_px, 1.0, 1024.0);
    r.integer(*t, "brush3d", "ink_volume_size", &b.ink_volume_size, 8, 256);
    r.integer(*t, "brush3d", "ink_seed", &b.ink_seed, 0, 0xffffffffll);
    r.integer(*t, "brush3d", "sample_size", &b.sample_size, 8, 512);
    r.number(*t, "brush3d", "slab_thickness", &b.slab_thickness, 0.01, 2.0);
    r.number(*t, "brush3d", "absorption", &b.absorption, 0.0, 1000.0);
    r.number(*t, "brush3d", "max_tilt_deg", &b.max_tilt_deg, 0.0, 80.0);
    r.number(*t, "brush3d", "pressure_quantum", &b.pressure_quantum, 1e-4, 0.25);
    r.number(*t, "brush3d", "tilt_quantum_deg", &b.tilt_quantum_deg, 0.01, 15.0);
    r.integer(*t, "brush3d", "cache_entries", &b.cache_entries, 0, 1 << 20);
  }
  if (const toml::table* t = r.section(root, "skeleton")) {
    SkeletonParams& s = c->skeleton;
    r.number(*t, "skeleton", "segment_length_px", &s.segment_length_px, 1.0, 512.0);
    r.number(*t, "skeleton", "time_step_ms", &s.time_step_ms, 0.1, 20.0);
    r.integer(*t, "skeleton", "constraint_iterations", &s.constraint_iterations, 1, 100);
    r.number(*t, "skeleton", "gravity_px_s2", &s.gravity_px_s2, 0.0, 1e7);
    r.number(*t, "skeleton", "damping", &s.damping, 0.0, 1.0);
    r.number(*t, "skeleton", "press_depth", &s.press_depth, 0.0, 1.0);
    r.number(*t, "skeleton", "paper_softness_px", &s.paper_softness_px, 0.1, 64.0);
    r.integer(*t, "skeleton", "bristles", &s.bristles, 1, 1000);
    r.number(*t, "skeleton", "bristle_spread_px", &s.bristle_spread_px, 0.0, 256.0);
    r.number(*t, "skeleton", "bristle_splay", &s.bristle_splay, 0.0, 10.0);
    r.number(*t, "skeleton", "bristle_radius_px", &s.bristle_radius_px, 0.1, 32.0);
    r.integer(*t, "skeleton", "bristle_points", &s.bristle_points, 2, 256);
    r.integer(*t, "skeleton", "max_steps_per_sample", &s.max_steps_per_sample, 1, 100000);
    r.number(*t, "skeleton", "stamp_spacing_px", &s.stamp_spacing_px, 0.0, 64.0);
    r.integer(*t, "skeleton", "end_settle_steps", &s.end_settle_steps, 0, 10000);
    r.integer(*t, "skeleton", "seed", &s.seed, 0, 0xffffffffll);
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
  std::ostringstream o;
  char buf[64];
  const auto num = [&](const char* key, double v) {
    std::snprintf(buf, sizeof buf, "%.9g", v);
    o << key << " = " << buf << "\n";
  };
  const auto integer = [&](const char* key, long long v) { o << key << " = " << v << "\n"; };
  o << "brush = \"" << brushKindName(c.default_brush) << "\"\n\n[stroke]\n";
  num("spacing_px", c.stroke.spacing_px);
  num("footprint_scale", c.stroke.footprint_scale);
  num("size", c.stroke.size);
  num("billow", c.stroke.billow);
  num("billow_length", c.stroke.billow_length);
  integer("auto_end_still_ms", c.stroke.auto_end_still_ms);
  integer("auto_end_light_ms", c.stroke.auto_end_light_ms);
  o << "auto_end_light_by_hysteresis = "
    << (c.stroke.auto_end_light_by_hysteresis ? "true" : "false") << "\n";
  o << "\n[dispersion]\n";
  num("slow_speed_px_s", c.dispersion.slow_speed_px_s);
  num("fast_speed_px_s", c.dispersion.fast_speed_px_s);
  num("max_dispersion", c.dispersion.max_dispersion);
  num("speed_smoothing_ms", c.dispersion.speed_smoothing_ms);
  num("noise_scale_px", c.dispersion.noise_scale_px);
  o << "\n[brush2d]\n";
  num("min_diameter_px", c.brush2d.min_diameter_px);
  num("max_diameter_px", c.brush2d.max_diameter_px);
  integer("texture_size", c.brush2d.texture_size);
  integer("bristles", c.brush2d.bristles);
  integer("texture_seed", c.brush2d.texture_seed);
  o << "\n[brush3d]\n";
  num("diameter_px", c.brush3d.diameter_px);
  integer("ink_volume_size", c.brush3d.ink_volume_size);
  integer("ink_seed", c.brush3d.ink_seed);
  integer("sample_size", c.brush3d.sample_size);
  num("slab_thickness", c.brush3d.slab_thickness);
  num("absorption", c.brush3d.absorption);
  num("max_tilt_deg", c.brush3d.max_tilt_deg);
  num("pressure_quantum", c.brush3d.pressure_quantum);
  num("tilt_quantum_deg", c.brush3d.tilt_quantum_deg);
  integer("cache_entries", c.brush3d.cache_entries);
  o << "\n[skeleton]\n";
  num("segment_length_px", c.skeleton.segment_length_px);
  num("time_step_ms", c.skeleton.time_step_ms);
  integer("constraint_iterations", c.skeleton.constraint_iterations);
  num("gravity_px_s2", c.skeleton.gravity_px_s2);
  num("damping", c.skeleton.damping);
  num("press_depth", c.skeleton.press_depth);
  num("paper_softness_px", c.skeleton.paper_softness_px);
  integer("bristles", c.skeleton.bristles);
  num("bristle_spread_px", c.skeleton.bristle_spread_px);
  num("bristle_splay", c.skeleton.bristle_splay);
  num("bristle_radius_px", c.skeleton.bristle_radius_px);
  integer("bristle_points", c.skeleton.bristle_points);
  integer("max_steps_per_sample", c.skeleton.max_steps_per_sample);
  num("stamp_spacing_px", c.skeleton.stamp_spacing_px);
  integer("end_settle_steps", c.skeleton.end_settle_steps);
  integer("seed", c.skeleton.seed);
  return o.str();
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
