#include "app/render/render_config.h"

#include <cfloat>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <toml++/toml.h>

#include "app/core/toml_file.h"
#include "app/scene/sun_position.h"
#include "drivers/core/toml_number.h"

namespace cb {
namespace {

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
  // Keys a table may hold; anything else is reported (a typo would otherwise pass silently).
  void onlyKeys(const toml::table* t, const std::string& table,
                std::initializer_list<const char*> keys) {
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

const toml::table* subTable(const toml::table& root, const char* section, const char* name) {
  const toml::table* s = root[section].as_table();
  return s ? (*s)[name].as_table() : nullptr;
}

void readStyleParams(const toml::table& root, Lenient& in, StyleParams* p) {
  const toml::table* t = subTable(root, "style", "physical");
  in.onlyKeys(t, "style.physical",
              {"reflection", "scattering", "forward_g", "back_g", "forward_weight", "octaves",
               "ambient", "exposure", "erosion"});
  in.real(t, "style.physical", "reflection", 0.0f, 4.0f, &p->physical.reflection);
  in.real(t, "style.physical", "scattering", 0.0f, 4.0f, &p->physical.scattering);
  in.real(t, "style.physical", "forward_g", -0.95f, 0.95f, &p->physical.forward_g);
  in.real(t, "style.physical", "back_g", -0.95f, 0.95f, &p->physical.back_g);
  in.real(t, "style.physical", "forward_weight", 0.0f, 1.0f, &p->physical.forward_weight);
  in.integer(t, "style.physical", "octaves", 1, 3, &p->physical.octaves);
  in.real(t, "style.physical", "ambient", 0.0f, 4.0f, &p->physical.ambient);
  in.real(t, "style.physical", "exposure", 0.1f, 10.0f, &p->physical.exposure);
  in.real(t, "style.physical", "erosion", 0.0f, 1.0f, &p->physical.erosion);
  t = subTable(root, "style", "ink");
  in.onlyKeys(t, "style.ink", {"wash", "line_width", "bleed_sigma", "sky"});
  in.real(t, "style.ink", "wash", 0.0f, 1.0f, &p->ink.wash);
  in.real(t, "style.ink", "line_width", 0.05f, 1.0f, &p->ink.line_width);
  in.real(t, "style.ink", "bleed_sigma", 0.3f, float(kMaxInkBleedRadius) / 2.1213f,
          &p->ink.bleed_sigma);
  in.boolean(t, "style.ink", "sky", &p->ink.sky);
  t = subTable(root, "style", "cartoon");
  in.onlyKeys(t, "style.cartoon", {"band_thresholds", "outline_width"});
  glm::vec3 bands = p->cartoon.band_thresholds;
  in.vec3(t, "style.cartoon", "band_thresholds", 0.0f, 1.0f, &bands);
  if (bands.x < bands.y && bands.y < bands.z)
    p->cartoon.band_thresholds = bands;
  else
    in.warn(*t->get("band_thresholds"), "style.cartoon.band_thresholds",
            "must rise from the first to the third", "the default");
  in.real(t, "style.cartoon", "outline_width", 0.02f, 1.0f, &p->cartoon.outline_width);
  t = subTable(root, "style", "sketch");
  in.onlyKeys(t, "style.sketch", {"outline_width", "sky"});
  in.real(t, "style.sketch", "outline_width", 0.02f, 1.0f, &p->sketch.outline_width);
  in.boolean(t, "style.sketch", "sky", &p->sketch.sky);
}

void readSky(const toml::table& root, const std::string& path, Lenient& in, SkySettings* sky) {
  const toml::table* t = root["sky"].as_table();
  if (!t) return;
  in.onlyKeys(t, "sky",
              {"kind", "zenith", "horizon", "sun_glow", "image", "lic_seed", "lic_size",
               "lic_length", "lic_coverage", "lic_scale"});
  in.vec3(t, "sky", "zenith", 0.0f, 1.0f, &sky->zenith);
  in.vec3(t, "sky", "horizon", 0.0f, 1.0f, &sky->horizon);
  in.real(t, "sky", "sun_glow", 0.0f, 4.0f, &sky->sun_glow);
  int seed = int(sky->lic_seed & 0x7fffffff);
  in.integer(t, "sky", "lic_seed", 0, 0x7fffffff, &seed);
  sky->lic_seed = uint32_t(seed);
  in.integer(t, "sky", "lic_size", 16, 4096, &sky->lic_size);
  in.integer(t, "sky", "lic_length", 1, 256, &sky->lic_length);
  in.real(t, "sky", "lic_coverage", 0.0f, 1.0f, &sky->lic_coverage);
  in.real(t, "sky", "lic_scale", 0.01f, 100.0f, &sky->lic_scale);
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
  const auto integer = [&](const char* key, long long v) {
    o += std::string(key) + " = " + std::to_string(v) + "\n";
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
  vec("direction", &c.light.direction.x, 3);  // after [light] time_of_day: that hour's sun
  vec("colour", &c.light.colour.x, 3);
  num("extinction", c.light.extinction);
  const SkySettings& sky = r.sky;
  o += std::string("\n[sky]\nkind = \"") + skyKindName(sky.kind) + "\"\n";
  vec("zenith", &sky.zenith.x, 3);
  vec("horizon", &sky.horizon.x, 3);
  num("sun_glow", sky.sun_glow);
  if (!sky.image_path.empty()) {
    std::ostringstream quoted;  // the path as a TOML string (escaped by toml++)
    quoted << toml::value<std::string>(sky.image_path);
    o += "image = " + quoted.str() + "\n";
  }
  integer("lic_seed", sky.lic_seed);
  integer("lic_size", sky.lic_size);
  integer("lic_length", sky.lic_length);
  num("lic_coverage", sky.lic_coverage);
  num("lic_scale", sky.lic_scale);
  const StyleParams& p = r.style_params;
  o += "\n[style.physical]\n";
  num("reflection", p.physical.reflection);
  num("scattering", p.physical.scattering);
  num("forward_g", p.physical.forward_g);
  num("back_g", p.physical.back_g);
  num("forward_weight", p.physical.forward_weight);
  integer("octaves", p.physical.octaves);
  num("ambient", p.physical.ambient);
  num("exposure", p.physical.exposure);
  num("erosion", p.physical.erosion);
  o += "\n[style.ink]\n";
  num("wash", p.ink.wash);
  num("line_width", p.ink.line_width);
  num("bleed_sigma", p.ink.bleed_sigma);
  o += std::string("sky = ") + (p.ink.sky ? "true" : "false") + "\n";
  o += "\n[style.cartoon]\n";
  vec("band_thresholds", &p.cartoon.band_thresholds.x, 3);
  num("outline_width", p.cartoon.outline_width);
  o += "\n[style.sketch]\n";
  num("outline_width", p.sketch.outline_width);
  o += std::string("sky = ") + (p.sketch.sky ? "true" : "false") + "\n";
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
  read(root, path, "raycast", "step_voxels", &o.step_voxels, 0.1, 8.0);
  read(root, path, "raycast", "extinction_per_voxel", &o.extinction_per_voxel, 0.0);
  read(root, path, "raycast", "termination_transmittance", &o.termination_transmittance, 0.0, 1.0);
  read(root, path, "raycast", "skip_empty_space", &o.skip_empty_space);
  read(root, path, "raycast", "brick_stepping", &o.brick_stepping);
  readVec<4>(root, path, "background", "colour", &o.background);
  if (auto node = root["style"]["name"]) {
    auto name = node.value<std::string>();
    auto style = name ? parseRenderStyle(*name) : std::nullopt;
    if (!style) bad(path, "style.name", "must be one of " + renderStyleNameList());
    o.style = *style;
  }
  read(root, path, "motion", "moving_scale", &c.moving_scale, 0.05, 1.0);
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
  readVec<3>(root, path, "light", "colour", &c.light.colour);
  read(root, path, "light", "extinction", &c.light.extinction, 0.0, 1.0);
  // The open ends the ranges above cannot say.
  if (!(o.extinction_per_voxel > 0.0f)) bad(path, "raycast.extinction_per_voxel", "must be > 0");
  if (!(o.termination_transmittance < 1.0f))
    bad(path, "raycast.termination_transmittance", "must be in [0, 1)");
  Lenient lenient(path, &c.warnings);
  readTimeOfDay(root, lenient, direction_given, &c.light);
  readStyleParams(root, lenient, &c.options.style_params);
  readSky(root, path, lenient, &c.options.sky);
  return c;
}
}  // namespace

}  // namespace cb
