#include "app/render/render_config.h"

#include <cfloat>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <toml++/toml.h>

#include "app/core/config_fields.h"
#include "app/core/toml_file.h"
#include "app/scene/sun_position.h"
#include "drivers/core/toml_number.h"

namespace cb {
namespace {

// The fields of render.toml, each listed once for reading and writing (config_fields.h), in the
// order the settings text lists them. Set by hand beside them: [style] name, [light] direction
// (or the older position, or time_of_day), [sky] kind and image.
//
// The strict part: a wrong type or value stops the program.
const ConfigField<RenderConfig> kStrictFields[] = {
    {"raycast", "step_voxels", [](RenderConfig& c) -> FieldRef { return &c.options.step_voxels; },
     0.1, 8.0},
    {"raycast", "extinction_per_voxel",
     [](RenderConfig& c) -> FieldRef { return &c.options.extinction_per_voxel; }, 0.0, FLT_MAX},
    {"raycast", "termination_transmittance",
     [](RenderConfig& c) -> FieldRef { return &c.options.termination_transmittance; }, 0.0, 1.0},
    {"raycast", "skip_empty_space",
     [](RenderConfig& c) -> FieldRef { return &c.options.skip_empty_space; }},
    {"raycast", "brick_stepping",
     [](RenderConfig& c) -> FieldRef { return &c.options.brick_stepping; }},
    {"background", "colour", [](RenderConfig& c) -> FieldRef { return &c.options.background; },
     -FLT_MAX, FLT_MAX},
    {"motion", "moving_scale", [](RenderConfig& c) -> FieldRef { return &c.moving_scale; }, 0.05,
     1.0},
    {"light", "colour", [](RenderConfig& c) -> FieldRef { return &c.light.colour; }, -FLT_MAX,
     FLT_MAX},
    {"light", "extinction", [](RenderConfig& c) -> FieldRef { return &c.light.extinction; }, 0.0,
     1.0},
};
// The newer settings warn and keep their default (Lenient). The sky's colours, then its LIC
// cloud layer (sky.image is written between them).
const ConfigField<RenderConfig> kSkyLookFields[] = {
    {"sky", "zenith", [](RenderConfig& c) -> FieldRef { return &c.options.sky.zenith; }, 0.0, 1.0},
    {"sky", "horizon", [](RenderConfig& c) -> FieldRef { return &c.options.sky.horizon; }, 0.0,
     1.0},
    {"sky", "sun_glow", [](RenderConfig& c) -> FieldRef { return &c.options.sky.sun_glow; }, 0.0,
     4.0},
};
const ConfigField<RenderConfig> kSkyLicFields[] = {
    {"sky", "lic_seed", [](RenderConfig& c) -> FieldRef { return &c.options.sky.lic_seed; }, 0,
     0x7fffffff},
    {"sky", "lic_size", [](RenderConfig& c) -> FieldRef { return &c.options.sky.lic_size; }, 16,
     4096},
    {"sky", "lic_length", [](RenderConfig& c) -> FieldRef { return &c.options.sky.lic_length; }, 1,
     256},
    {"sky", "lic_coverage", [](RenderConfig& c) -> FieldRef { return &c.options.sky.lic_coverage; },
     0.0, 1.0},
    {"sky", "lic_scale", [](RenderConfig& c) -> FieldRef { return &c.options.sky.lic_scale; }, 0.01,
     100.0},
};
// Each style's parameters (render_style_params.h), a [style.NAME] table per style.
const ConfigField<RenderConfig> kStyleFields[] = {
    {"style.physical", "reflection",
     [](RenderConfig& c) -> FieldRef { return &c.options.style_params.physical.reflection; }, 0.0,
     4.0},
    {"style.physical", "scattering",
     [](RenderConfig& c) -> FieldRef { return &c.options.style_params.physical.scattering; }, 0.0,
     4.0},
    {"style.physical", "forward_g",
     [](RenderConfig& c) -> FieldRef { return &c.options.style_params.physical.forward_g; }, -0.95,
     0.95},
    {"style.physical", "back_g",
     [](RenderConfig& c) -> FieldRef { return &c.options.style_params.physical.back_g; }, -0.95,
     0.95},
    {"style.physical", "forward_weight",
     [](RenderConfig& c) -> FieldRef { return &c.options.style_params.physical.forward_weight; },
     0.0, 1.0},
    {"style.physical", "octaves",
     [](RenderConfig& c) -> FieldRef { return &c.options.style_params.physical.octaves; }, 1, 3},
    {"style.physical", "ambient",
     [](RenderConfig& c) -> FieldRef { return &c.options.style_params.physical.ambient; }, 0.0,
     4.0},
    {"style.physical", "exposure",
     [](RenderConfig& c) -> FieldRef { return &c.options.style_params.physical.exposure; }, 0.1,
     10.0},
    {"style.physical", "erosion",
     [](RenderConfig& c) -> FieldRef { return &c.options.style_params.physical.erosion; }, 0.0,
     1.0},
    {"style.ink", "wash",
     [](RenderConfig& c) -> FieldRef { return &c.options.style_params.ink.wash; }, 0.0, 1.0},
    {"style.ink", "line_width",
     [](RenderConfig& c) -> FieldRef { return &c.options.style_params.ink.line_width; }, 0.05, 1.0},
    {"style.ink", "bleed_sigma",
     [](RenderConfig& c) -> FieldRef { return &c.options.style_params.ink.bleed_sigma; }, 0.3,
     float(kMaxInkBleedRadius) / 2.1213f},
    {"style.ink", "sky",
     [](RenderConfig& c) -> FieldRef { return &c.options.style_params.ink.sky; }},
    {"style.cartoon", "band_thresholds",
     [](RenderConfig& c) -> FieldRef { return &c.options.style_params.cartoon.band_thresholds; },
     0.0, 1.0},
    {"style.cartoon", "outline_width",
     [](RenderConfig& c) -> FieldRef { return &c.options.style_params.cartoon.outline_width; },
     0.02, 1.0},
    {"style.sketch", "outline_width",
     [](RenderConfig& c) -> FieldRef { return &c.options.style_params.sketch.outline_width; }, 0.02,
     1.0},
    {"style.sketch", "sky",
     [](RenderConfig& c) -> FieldRef { return &c.options.style_params.sketch.sky; }},
};

[[noreturn]] void bad(const std::string& path, const std::string& key, const std::string& what) {
  throw std::runtime_error(path + ": " + key + " " + what);
}

// A setting of the strict part of the file: a wrong type or value stops the program with
// "FILE:LINE: section.key: what". Numbers are finite, in lo..hi and refused before any
// conversion (1e40 does not fit a float, NaN is in no range).
template <class T>
void read(const toml::table& root, const std::string& path, const char* section, const char* key,
          T* out, double lo = -FLT_MAX, double hi = FLT_MAX) {
  auto node = root[section][key];
  if (!node) return;
  if constexpr (std::is_same_v<T, bool>) {
    auto v = node.template value<bool>();
    if (!v) bad(path, std::string(section) + "." + key, "must be true or false");
    *out = *v;
  } else {
    std::string why;
    const auto v =
        toml_number::numberIn(*node.node(), path, std::string(section) + "." + key, lo, hi, &why);
    if (!v) throw std::runtime_error(why);
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
    std::string why;
    const auto v = toml_number::numberIn((*a)[size_t(i)], path, name, -FLT_MAX, FLT_MAX, &why);
    if (!v) throw std::runtime_error(why);
    (*out)[i] = float(*v);
  }
  return true;
}

// The newer settings warn and keep their default instead of stopping the program:
// "FILE:LINE:COL: key what; using the default D".
class Lenient {
 public:
  Lenient(const std::string& path, std::vector<std::string>* warnings)
      : path_(path), warnings_(warnings) {}

  std::string where(const toml::node& n) const {
    const toml::source_region& r = n.source();
    return path_ + ":" + std::to_string(r.begin.line) + ":" + std::to_string(r.begin.column);
  }
  void warn(const toml::node& n, const std::string& key, const std::string& what,
            const std::string& fallback) {
    note(where(n) + ": " + key + " " + what + "; using " + fallback);
  }
  void note(const std::string& line) {
    warnings_->push_back(line);
    std::fprintf(stderr, "cloudbrush: %s\n", line.c_str());
  }
  static std::string number(double v) {
    std::ostringstream o;
    o << v;
    return o.str();
  }

  void real(const toml::table* t, const std::string& table, const char* key, float lo, float hi,
            float* out) {
    const toml::node* n = t ? t->get(key) : nullptr;
    if (!n) return;
    const auto v = toml_number::numberIn(*n, path_, table + "." + key, lo, hi, nullptr);
    const std::string range = "[" + number(lo) + ", " + number(hi) + "]";
    if (!v)
      warn(*n, table + "." + key,
           n->is_number() ? "must be in " + range : "must be a number in " + range,
           "the default " + number(*out));
    else
      *out = float(*v);
  }
  void integer(const toml::table* t, const std::string& table, const char* key, int64_t lo,
               int64_t hi, int* out) {
    const toml::node* n = t ? t->get(key) : nullptr;
    if (!n) return;
    auto v = n->value_exact<int64_t>();
    const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    if (!v || *v < lo || *v > hi)
      warn(*n, table + "." + key, "must be a whole number in " + range,
           "the default " + std::to_string(*out));
    else
      *out = int(*v);
  }
  void boolean(const toml::table* t, const std::string& table, const char* key, bool* out) {
    const toml::node* n = t ? t->get(key) : nullptr;
    if (!n) return;
    auto v = n->value_exact<bool>();
    if (!v)
      warn(*n, table + "." + key, "must be true or false",
           std::string("the default ") + (*out ? "true" : "false"));
    else
      *out = *v;
  }
  // Three numbers in [lo, hi] (colours, thresholds).
  void vec3(const toml::table* t, const std::string& table, const char* key, float lo, float hi,
            glm::vec3* out) {
    const toml::node* n = t ? t->get(key) : nullptr;
    if (!n) return;
    const toml::array* a = n->as_array();
    glm::vec3 v(0.0f);
    bool ok = a && a->size() == 3;
    for (size_t i = 0; ok && i < 3; ++i) {
      const auto x = toml_number::numberIn((*a)[i], path_, table + "." + key, lo, hi, nullptr);
      ok = x.has_value();
      if (ok) v[int(i)] = float(*x);
    }
    if (!ok)
      warn(*n, table + "." + key,
           "must be an array of 3 numbers in [" + number(lo) + ", " + number(hi) + "]",
           "the default [" + number((*out)[0]) + ", " + number((*out)[1]) + ", " +
               number((*out)[2]) + "]");
    else
      *out = v;
  }
  // One row of a field list, by its member's type (a uint32_t is read as a whole number).
  void field(const toml::table* t, const ConfigField<RenderConfig>& f, RenderConfig& c) {
    std::visit(
        [&](auto* member) {
          using T = std::remove_pointer_t<decltype(member)>;
          if constexpr (std::is_same_v<T, float>) {
            real(t, f.section, f.key, float(f.lo), float(f.hi), member);
          } else if constexpr (std::is_same_v<T, int>) {
            integer(t, f.section, f.key, int64_t(f.lo), int64_t(f.hi), member);
          } else if constexpr (std::is_same_v<T, uint32_t>) {
            int v = int(*member & 0x7fffffff);
            integer(t, f.section, f.key, int64_t(f.lo), int64_t(f.hi), &v);
            *member = uint32_t(v);
          } else if constexpr (std::is_same_v<T, bool>) {
            boolean(t, f.section, f.key, member);
          } else if constexpr (std::is_same_v<T, glm::vec3>) {
            vec3(t, f.section, f.key, float(f.lo), float(f.hi), member);
          }
        },
        f.at(c));
  }
  // Keys a table may hold; anything else is reported (a typo would otherwise pass silently).
  void onlyKeys(const toml::table* t, const std::string& table,
                const std::vector<const char*>& keys) {
    if (!t) return;
    for (const auto& [k, node] : *t) {
      bool known = false;
      for (const char* key : keys) known |= k.str() == key;
      if (known) continue;
      std::string list;
      for (const char* key : keys) list += (list.empty() ? "" : ", ") + std::string(key);
      warn(node, table + "." + std::string(k.str()), "is not a setting (known: " + list + ")",
           "nothing from it");
    }
  }

 private:
  std::string path_;
  std::vector<std::string>* warnings_;
};

// The keys of `section` in `fields`, with `extra` (set by hand) in front.
std::vector<const char*> keysOf(std::span<const ConfigField<RenderConfig>> fields,
                                std::string_view section, std::vector<const char*> extra = {}) {
  for (const ConfigField<RenderConfig>& f : fields)
    if (section == f.section) extra.push_back(f.key);
  return extra;
}

// [style.NAME]: each style's parameters.
void readStyleParams(const toml::table& root, Lenient& in, RenderConfig* c) {
  const glm::vec3 bands = c->options.style_params.cartoon.band_thresholds;
  std::string_view open;
  const toml::table* t = nullptr;
  for (const ConfigField<RenderConfig>& f : kStyleFields) {
    if (f.section != open) {
      open = f.section;
      t = root.at_path(f.section).as_table();
      in.onlyKeys(t, f.section, keysOf(kStyleFields, f.section));
    }
    in.field(t, f, *c);
  }
  glm::vec3& read = c->options.style_params.cartoon.band_thresholds;
  if (!(read.x < read.y && read.y < read.z)) {
    in.warn(*root.at_path("style.cartoon.band_thresholds").node(), "style.cartoon.band_thresholds",
            "must rise from the first to the third", "the default");
    read = bands;
  }
}

void readSky(const toml::table& root, const std::string& path, Lenient& in, RenderConfig* c) {
  SkySettings* sky = &c->options.sky;
  const toml::table* t = root["sky"].as_table();
  if (!t) return;
  std::vector<const char*> keys = keysOf(kSkyLookFields, "sky", {"kind"});
  keys.push_back("image");
  in.onlyKeys(t, "sky", keysOf(kSkyLicFields, "sky", keys));
  for (const ConfigField<RenderConfig>& f : kSkyLookFields) in.field(t, f, *c);
  for (const ConfigField<RenderConfig>& f : kSkyLicFields) in.field(t, f, *c);
  const toml::node* kind = t->get("kind");
  if (kind) {
    auto name = kind->value<std::string>();
    SkyKind k;
    if (!name || !parseSkyKind(*name, &k))
      in.warn(*kind, "sky.kind", "must be one of none|colour|lic|image", "the default \"none\"");
    else
      sky->kind = k;
  }
  const toml::node* image = t->get("image");
  if (image) {
    auto file = image->value<std::string>();
    if (!file)
      in.warn(*image, "sky.image", "must be a file name (a PNG)", "no image");
    else
      // Relative to the config file's folder, so a config can ship its picture beside it.
      sky->image_path = std::filesystem::path(*file).is_absolute()
                            ? *file
                            : (std::filesystem::path(path).parent_path() / *file).string();
  }
  if (sky->kind != SkyKind::kImage) return;
  const toml::node& at = image ? *image : kind ? *kind : *static_cast<const toml::node*>(t);
  if (sky->image_path.empty()) {
    in.warn(at, "sky.kind", "is \"image\" but sky.image names no PNG", "the sky kind \"none\"");
    sky->kind = SkyKind::kNone;
    return;
  }
  try {
    sky->image = std::make_shared<const ImageRgba8>(readPng(sky->image_path, kMaxSkyImagePixels));
  } catch (const std::exception& e) {
    in.warn(at, "sky.image", std::string("cannot be used: ") + e.what(), "the sky kind \"none\"");
    sky->kind = SkyKind::kNone;
  }
}

// [light] time_of_day (+ latitude, day_of_year): the sun of that hour; it wins over direction.
void readTimeOfDay(const toml::table& root, Lenient& in, bool direction_given, Light* light) {
  const toml::table* t = root["light"].as_table();
  const toml::node* n = t ? t->get("time_of_day") : nullptr;
  if (!n) return;
  float latitude = kDefaultLatitudeDeg;
  int day = kDefaultDayOfYear;
  in.real(t, "light", "latitude", -90.0f, 90.0f, &latitude);
  in.integer(t, "light", "day_of_year", 1, 366, &day);
  auto text = n->value<std::string>();
  float hours = 0.0f;
  if (!text || !parseTimeOfDay(text->c_str(), &hours)) {
    in.warn(*n, "light.time_of_day", "must be \"HH:MM\" (00:00 to 23:59)",
            direction_given ? "light.direction" : "the default sun direction");
    return;
  }
  SunPosition sun = sunPosition(hours, latitude, day);
  char where[128];
  std::snprintf(where, sizeof where,
                "%s at latitude %g, day %d: sun elevation %.1f°, azimuth %.1f°", text->c_str(),
                double(latitude), day, double(sun.elevation_deg), double(sun.azimuth_deg));
  if (sun.elevation_deg < 1.0f) {
    // Below the horizon the clouds would be lit from underneath, in the dark: keep the azimuth
    // and put the sun just above the horizon.
    const float az = sun.azimuth_deg * 0.017453292519943295f, el = 0.017453292519943295f;
    sun.direction =
        glm::vec3(std::cos(el) * std::sin(az), std::sin(el), -std::cos(el) * std::cos(az));
    in.note(in.where(*n) + ": light.time_of_day " + where +
            " is below the horizon; lighting from 1° above it");
    sun.elevation_deg = 1.0f;
  } else {
    in.note(in.where(*n) + ": light.time_of_day " + where +
            (direction_given ? " (it wins over light.direction)" : ""));
  }
  light->direction = sun.direction;
  light->colour *= sunTransmittance(sun.elevation_deg);
}

}  // namespace

namespace {
RenderConfig renderConfigFrom(const toml::table& root, const std::string& path);
}  // namespace

std::string formatRenderConfig(const RenderConfig& c) {
  std::string o = "[raycast]\n";
  appendSection<RenderConfig>(o, kStrictFields, c, "raycast");
  o += "\n[background]\n";
  appendSection<RenderConfig>(o, kStrictFields, c, "background");
  o += std::string("\n[style]\nname = \"") + renderStyleName(c.options.style) + "\"\n\n[motion]\n";
  appendSection<RenderConfig>(o, kStrictFields, c, "motion");
  o += "\n[light]\n";
  glm::vec3 direction = c.light.direction;  // after [light] time_of_day: that hour's sun
  appendField(o, "direction", &direction);
  appendSection<RenderConfig>(o, kStrictFields, c, "light");
  const SkySettings& sky = c.options.sky;
  o += std::string("\n[sky]\nkind = \"") + skyKindName(sky.kind) + "\"\n";
  appendSection<RenderConfig>(o, kSkyLookFields, c, "sky");
  if (!sky.image_path.empty()) {
    std::ostringstream quoted;  // the path as a TOML string (escaped by toml++)
    quoted << toml::value<std::string>(sky.image_path);
    o += "image = " + quoted.str() + "\n";
  }
  appendSection<RenderConfig>(o, kSkyLicFields, c, "sky");
  appendSections<RenderConfig>(o, kStyleFields, c);
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
  for (const ConfigField<RenderConfig>& f : kStrictFields)
    std::visit(
        [&](auto* member) {
          using T = std::remove_pointer_t<decltype(member)>;
          if constexpr (std::is_same_v<T, glm::vec3> || std::is_same_v<T, glm::vec4>)
            readVec<T::length()>(root, path, f.section, f.key, member);
          else
            read(root, path, f.section, f.key, member, f.lo, f.hi);
        },
        f.at(c));
  if (auto node = root["style"]["name"]) {
    auto name = node.value<std::string>();
    auto style = name ? parseRenderStyle(*name) : std::nullopt;
    if (!style) bad(path, "style.name", "must be one of " + renderStyleNameList());
    o.style = *style;
  }
  // light.direction points towards the sun; the older light.position (a light ball seen from
  // the origin) gives the same direction.
  glm::vec3 towards(0.0f);
  if (readVec<3>(root, path, "light", "position", &towards) && glm::length(towards) > 0.0f)
    c.light.direction = Light::directionTowards(towards);
  bool direction_given = false;
  if (readVec<3>(root, path, "light", "direction", &towards) && glm::length(towards) > 0.0f) {
    c.light.direction = Light::directionTowards(towards);
    direction_given = true;
  }
  // The open ends the ranges above cannot say.
  if (!(o.extinction_per_voxel > 0.0f)) bad(path, "raycast.extinction_per_voxel", "must be > 0");
  if (!(o.termination_transmittance < 1.0f))
    bad(path, "raycast.termination_transmittance", "must be in [0, 1)");
  Lenient lenient(path, &c.warnings);
  readTimeOfDay(root, lenient, direction_given, &c.light);
  readStyleParams(root, lenient, &c);
  readSky(root, path, lenient, &c);
  return c;
}
}  // namespace

}  // namespace cb
