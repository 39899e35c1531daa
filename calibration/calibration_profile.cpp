#include "calibration/calibration_profile.h"

#include <toml++/toml.h>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include "drivers/core/toml_number.h"

namespace cb {

bool DeviceMatch::matches(const PenDeviceInfo& device, uint64_t serial) const {
  if (usb_vendor && *usb_vendor != device.usb_vendor) return false;
  if (usb_product && *usb_product != device.usb_product) return false;
  if (tool_serial != 0 && tool_serial != serial) return false;
  return true;
}

std::string DeviceMatch::describe() const {
  if (anyDevice() && tool_serial == 0) return "any device";
  char buf[96];
  std::snprintf(buf, sizeof buf, "%04x:%04x", usb_vendor.value_or(0), usb_product.value_or(0));
  std::string s = buf;
  if (tool_serial != 0) {
    std::snprintf(buf, sizeof buf, " tool serial 0x%llx",
                  static_cast<unsigned long long>(tool_serial));
    s += buf;
  }
  return s;
}

namespace {

// Reads typed, range-checked values out of a parsed table, collecting "file:line: ..." errors
// and warnings for keys nobody asked for.
class ProfileReader {
 public:
  ProfileReader(const std::string& source, ProfileParseResult* result)
      : source_(source), result_(result) {}

  std::string where(const toml::source_region& r) const {
    return source_ + ":" + std::to_string(r.begin.line);
  }
  void error(const toml::node& n, const std::string& what) {
    result_->errors.push_back(where(n.source()) + ": " + what);
  }

  // The sub-table `key` of `t`, or null when absent (an error when it is not a table).
  const toml::table* table(const toml::table& t, const std::string& key) {
    const toml::node* n = t.get(key);
    if (!n) return nullptr;
    if (!n->is_table()) {
      error(*n, "[" + key + "] must be a table");
      return nullptr;
    }
    return n->as_table();
  }

  void number(const toml::table& t, const std::string& section, const std::string& key, double lo,
              double hi, double* out) {
    const toml::node* n = t.get(key);
    if (!n) return;
    std::string why;  // NaN, infinities, booleans and strings refused
    const auto v = toml_number::numberIn(*n, source_, section + "." + key, lo, hi, &why);
    if (v)
      *out = *v;
    else
      result_->errors.push_back(why);
  }
  void number(const toml::table& t, const std::string& section, const std::string& key, double lo,
              double hi, float* out) {
    double d = *out;
    number(t, section, key, lo, hi, &d);
    *out = static_cast<float>(d);
  }

  void boolean(const toml::table& t, const std::string& section, const std::string& key,
               bool* out) {
    const toml::node* n = t.get(key);
    if (!n) return;
    if (!n->is_boolean()) {
      error(*n, section + "." + key + " must be true or false");
      return;
    }
    *out = n->as_boolean()->get();
  }

  std::optional<std::string> string(const toml::table& t, const std::string& section,
                                    const std::string& key) {
    const toml::node* n = t.get(key);
    if (!n) return std::nullopt;
    if (!n->is_string()) {
      error(*n, section + "." + key + " must be a string");
      return std::nullopt;
    }
    return n->as_string()->get();
  }

  std::optional<int64_t> integer(const toml::table& t, const std::string& section,
                                 const std::string& key, int64_t lo, int64_t hi) {
    const toml::node* n = t.get(key);
    if (!n) return std::nullopt;
    if (!n->is_integer()) {
      error(*n, section + "." + key + " must be an integer");
      return std::nullopt;
    }
    const int64_t v = n->as_integer()->get();
    if (v < lo || v > hi) {
      error(*n, section + "." + key + " = " + std::to_string(v) + " is outside " +
                    std::to_string(lo) + ".." + std::to_string(hi));
      return std::nullopt;
    }
    return v;
  }

  // An array of exactly `count` finite numbers.
  bool numbers(const toml::table& t, const std::string& section, const std::string& key,
               size_t count, std::vector<double>* out) {
    const toml::node* n = t.get(key);
    if (!n) return false;
    const toml::array* arr = n->as_array();
    if (!arr || arr->size() != count) {
      error(*n, section + "." + key + " must be an array of " + std::to_string(count) + " numbers");
      return false;
    }
    out->clear();
    for (const toml::node& e : *arr) {
      const auto v =
          toml_number::numberIn(e, source_, section + "." + key, -DBL_MAX, DBL_MAX, nullptr);
      if (!v) {
        error(e, section + "." + key + " must hold finite numbers only");
        return false;
      }
      out->push_back(*v);
    }
    return true;
  }

  void unknownKeys(const toml::table& t, const std::string& section,
                   std::initializer_list<const char*> known) {
    std::set<std::string> k(known.begin(), known.end());
    for (const auto& [key, node] : t) {
      if (!k.count(std::string(key.str()))) {
        result_->warnings.push_back(where(node.source()) + ": unknown key " +
                                    (section.empty() ? "" : section + ".") +
                                    std::string(key.str()) + " (ignored)");
      }
    }
  }

 private:
  std::string source_;
  ProfileParseResult* result_;
};

void readDevice(ProfileReader& r, const toml::table& t, DeviceMatch* d) {
  if (auto v = r.integer(t, "device", "usb_vendor", 0, 0xffff)) d->usb_vendor = *v;
  if (auto v = r.integer(t, "device", "usb_product", 0, 0xffff)) d->usb_product = *v;
  if (auto v = r.integer(t, "device", "tool_serial", 0, INT64_MAX)) d->tool_serial = *v;
  if (auto v = r.string(t, "device", "name")) d->name = *v;
  r.unknownKeys(t, "device", {"usb_vendor", "usb_product", "tool_serial", "name"});
}

void readArea(ProfileReader& r, const toml::table& t, AreaMappingConfig* a) {
  if (auto v = r.string(t, "area", "fit")) {
    if (!parseAreaFit(*v, &a->fit)) {
      r.error(*t.get("fit"), "area.fit = \"" + *v + "\" is not stretch, fit, letterbox or display");
    }
  }
  std::vector<double> n;
  if (r.numbers(t, "area", "tablet_mm", 4, &n)) a->tablet_area_mm = RectD{n[0], n[1], n[2], n[3]};
  if (r.numbers(t, "area", "screen_px", 4, &n)) a->screen_region_px = RectD{n[0], n[1], n[2], n[3]};
  r.number(t, "area", "rotation_deg", -360.0, 360.0, &a->rotation_deg);
  r.unknownKeys(t, "area", {"fit", "tablet_mm", "screen_px", "rotation_deg"});
}

void readFit(ProfileReader& r, const toml::table& t, CalibrationProfile* p) {
  if (auto v = r.string(t, "fit", "kind")) {
    if (!parsePointFitKind(*v, &p->fit_kind)) {
      r.error(*t.get("kind"), "fit.kind = \"" + *v + "\" is not none, affine or homography");
    }
  }
  std::vector<double> m;
  if (r.numbers(t, "fit", "matrix", 9, &m)) {
    for (int row = 0; row < 3; ++row)
      for (int col = 0; col < 3; ++col) p->correction[col][row] = m[row * 3 + col];
    if (std::abs(glm::determinant(p->correction)) < 1e-12) {
      r.error(*t.get("matrix"), "fit.matrix is singular");
    }
  }
  r.number(t, "fit", "rms_px", 0.0, 1e6, &p->fit_rms_px);
  r.number(t, "fit", "max_px", 0.0, 1e6, &p->fit_max_px);
  if (auto v = r.integer(t, "fit", "points", 0, 1000)) p->fit_points = static_cast<int>(*v);
  r.unknownKeys(t, "fit", {"kind", "matrix", "rms_px", "max_px", "points"});
}

void readPressure(ProfileReader& r, const toml::table& t, PressureSettings* p) {
  std::vector<double> c;
  if (r.numbers(t, "pressure", "curve", 4, &c)) {
    std::array<double, 4> pts{c[0], c[1], c[2], c[3]};
    if (std::string why = validatePressCurve(pts); !why.empty()) {
      r.error(*t.get("curve"), why);
    } else {
      p->curve = pts;
    }
  }
  r.number(t, "pressure", "contact_down", 0.0, 1.0, &p->contact.down);
  r.number(t, "pressure", "contact_up", 0.0, 1.0, &p->contact.up);
  if (p->contact.up > p->contact.down) {
    r.error(t, "pressure.contact_up must not exceed pressure.contact_down");
  }
  r.number(t, "pressure", "max_nib_offset", 0.0, 0.9, &p->nib.max_offset);
  r.number(t, "pressure", "hover_high_distance", 0.0, 1.0, &p->nib.hover_high_distance);
  r.number(t, "pressure", "light_target", 0.0, 0.9, &p->light_target);
  r.unknownKeys(t, "pressure",
                {"curve", "contact_down", "contact_up", "max_nib_offset", "hover_high_distance",
                 "light_target"});
}

void readOneEuro(ProfileReader& r, const toml::table& t, const std::string& section,
                 OneEuroParams* p) {
  r.number(t, section, "min_cutoff_hz", 1e-3, 1000.0, &p->min_cutoff_hz);
  r.number(t, section, "beta", 0.0, 100.0, &p->beta);
  r.number(t, section, "d_cutoff_hz", 1e-3, 1000.0, &p->d_cutoff_hz);
  r.unknownKeys(t, section, {"min_cutoff_hz", "beta", "d_cutoff_hz"});
}

// Doubles printed in the shortest form that reads back to the same value.
std::string num(double v) {
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof buf, v);
  std::string s(buf, res.ptr);
  if (s.find_first_of(".eE") == std::string::npos && s.find("inf") == std::string::npos &&
      s.find("nan") == std::string::npos) {
    s += ".0";
  }
  return s;
}

std::string hex4(uint16_t v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%04x", v);
  return buf;
}

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += ch;
    } else if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

}  // namespace

ProfileParseResult parseCalibrationProfile(std::string_view text, const std::string& source_name) {
  ProfileParseResult result;
  CalibrationProfile p;
  toml::table root;
  try {
    root = toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    result.errors.push_back(source_name + ":" + std::to_string(e.source().begin.line) + ": " +
                            std::string(e.description()));
    return result;
  }
  ProfileReader r(source_name, &result);
  if (const auto* t = r.table(root, "device")) readDevice(r, *t, &p.device);
  if (const auto* t = r.table(root, "area")) readArea(r, *t, &p.area);
  if (const auto* t = r.table(root, "fit")) readFit(r, *t, &p);
  if (const auto* t = r.table(root, "pressure")) readPressure(r, *t, &p.pressure);
  if (const auto* t = r.table(root, "tilt")) {
    r.number(*t, "tilt", "zero_x_deg", -45.0, 45.0, &p.tilt_zero.x_deg);
    r.number(*t, "tilt", "zero_y_deg", -45.0, 45.0, &p.tilt_zero.y_deg);
    r.unknownKeys(*t, "tilt", {"zero_x_deg", "zero_y_deg"});
  }
  if (const auto* t = r.table(root, "smoothing")) {
    if (const auto* s = r.table(*t, "position")) {
      readOneEuro(r, *s, "smoothing.position", &p.smoothing.position);
    }
    if (const auto* s = r.table(*t, "tilt"))
      readOneEuro(r, *s, "smoothing.tilt", &p.smoothing.tilt);
    r.unknownKeys(*t, "smoothing", {"position", "tilt"});
  }
  if (const auto* t = r.table(root, "prediction")) {
    r.number(*t, "prediction", "horizon_ms", 0.0, 200.0, &p.prediction.horizon_ms);
    r.number(*t, "prediction", "velocity_cutoff_hz", 1e-3, 1000.0,
             &p.prediction.velocity_cutoff_hz);
    r.boolean(*t, "prediction", "compensate_filter_lag", &p.prediction.compensate_filter_lag);
    r.number(*t, "prediction", "max_distance_mm", 0.0, 1000.0, &p.prediction.max_distance_mm);
    r.unknownKeys(*t, "prediction",
                  {"horizon_ms", "velocity_cutoff_hz", "compensate_filter_lag", "max_distance_mm"});
  }
  r.unknownKeys(root, "", {"device", "area", "fit", "pressure", "tilt", "smoothing", "prediction"});
  if (result.errors.empty()) result.profile = p;
  return result;
}

ProfileParseResult readCalibrationProfile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    ProfileParseResult r;
    r.errors.push_back(path + ": cannot be opened");
    return r;
  }
  std::stringstream ss;
  ss << in.rdbuf();
  return parseCalibrationProfile(ss.str(), path);
}

std::string formatCalibrationProfile(const CalibrationProfile& p) {
  std::ostringstream o;
  o << "# cloudbrush calibration profile\n";
  if (!p.device.anyDevice() || p.device.tool_serial != 0 || !p.device.name.empty()) {
    o << "\n[device]\n";
    if (!p.device.name.empty()) o << "name = " << quoted(p.device.name) << "\n";
    if (p.device.usb_vendor) o << "usb_vendor = " << hex4(*p.device.usb_vendor) << "\n";
    if (p.device.usb_product) o << "usb_product = " << hex4(*p.device.usb_product) << "\n";
    if (p.device.tool_serial != 0) o << "tool_serial = " << p.device.tool_serial << "\n";
  }
  o << "\n[area]\nfit = \"" << areaFitName(p.area.fit) << "\"\n";
  if (const auto& a = p.area.tablet_area_mm) {
    o << "tablet_mm = [" << num(a->x) << ", " << num(a->y) << ", " << num(a->w) << ", " << num(a->h)
      << "]\n";
  }
  if (const auto& s = p.area.screen_region_px) {
    o << "screen_px = [" << num(s->x) << ", " << num(s->y) << ", " << num(s->w) << ", " << num(s->h)
      << "]\n";
  }
  o << "rotation_deg = " << num(p.area.rotation_deg) << "\n";

  o << "\n[fit]\nkind = \"" << pointFitKindName(p.fit_kind) << "\"\nmatrix = [";
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col)
      o << num(p.correction[col][row]) << (row * 3 + col < 8 ? ", " : "");
  o << "]\nrms_px = " << num(p.fit_rms_px) << "\nmax_px = " << num(p.fit_max_px)
    << "\npoints = " << p.fit_points << "\n";

  const auto& pr = p.pressure;
  o << "\n[pressure]\ncurve = [" << num(pr.curve[0]) << ", " << num(pr.curve[1]) << ", "
    << num(pr.curve[2]) << ", " << num(pr.curve[3]) << "]\n"
    << "contact_down = " << num(pr.contact.down) << "\ncontact_up = " << num(pr.contact.up)
    << "\nmax_nib_offset = " << num(pr.nib.max_offset)
    << "\nhover_high_distance = " << num(pr.nib.hover_high_distance)
    << "\nlight_target = " << num(pr.light_target) << "\n";

  o << "\n[tilt]\nzero_x_deg = " << num(p.tilt_zero.x_deg)
    << "\nzero_y_deg = " << num(p.tilt_zero.y_deg) << "\n";

  auto euro = [&](const char* name, const OneEuroParams& e) {
    o << "\n[smoothing." << name << "]\nmin_cutoff_hz = " << num(e.min_cutoff_hz)
      << "\nbeta = " << num(e.beta) << "\nd_cutoff_hz = " << num(e.d_cutoff_hz) << "\n";
  };
  euro("position", p.smoothing.position);
  euro("tilt", p.smoothing.tilt);

  o << "\n[prediction]\nhorizon_ms = " << num(p.prediction.horizon_ms)
    << "\nvelocity_cutoff_hz = " << num(p.prediction.velocity_cutoff_hz)
    << "\ncompensate_filter_lag = " << (p.prediction.compensate_filter_lag ? "true" : "false")
    << "\nmax_distance_mm = " << num(p.prediction.max_distance_mm) << "\n";
  return o.str();
}

namespace {
bool sameRect(const std::optional<RectD>& a, const std::optional<RectD>& b) {
  if (a.has_value() != b.has_value()) return false;
  return !a || (a->x == b->x && a->y == b->y && a->w == b->w && a->h == b->h);
}
bool sameEuro(const OneEuroParams& a, const OneEuroParams& b) {
  return a.min_cutoff_hz == b.min_cutoff_hz && a.beta == b.beta && a.d_cutoff_hz == b.d_cutoff_hz;
}
}  // namespace

bool operator==(const CalibrationProfile& a, const CalibrationProfile& b) {
  return a.device.usb_vendor == b.device.usb_vendor &&
         a.device.usb_product == b.device.usb_product &&
         a.device.tool_serial == b.device.tool_serial && a.device.name == b.device.name &&
         a.area.fit == b.area.fit && sameRect(a.area.tablet_area_mm, b.area.tablet_area_mm) &&
         sameRect(a.area.screen_region_px, b.area.screen_region_px) &&
         a.area.rotation_deg == b.area.rotation_deg && a.fit_kind == b.fit_kind &&
         a.correction == b.correction && a.fit_rms_px == b.fit_rms_px &&
         a.fit_max_px == b.fit_max_px && a.fit_points == b.fit_points &&
         a.pressure.curve == b.pressure.curve &&
         a.pressure.contact.down == b.pressure.contact.down &&
         a.pressure.contact.up == b.pressure.contact.up &&
         a.pressure.nib.max_offset == b.pressure.nib.max_offset &&
         a.pressure.nib.hover_high_distance == b.pressure.nib.hover_high_distance &&
         a.pressure.light_target == b.pressure.light_target &&
         a.tilt_zero.x_deg == b.tilt_zero.x_deg && a.tilt_zero.y_deg == b.tilt_zero.y_deg &&
         sameEuro(a.smoothing.position, b.smoothing.position) &&
         sameEuro(a.smoothing.tilt, b.smoothing.tilt) &&
         a.prediction.horizon_ms == b.prediction.horizon_ms &&
         a.prediction.velocity_cutoff_hz == b.prediction.velocity_cutoff_hz &&
         a.prediction.compensate_filter_lag == b.prediction.compensate_filter_lag &&
         a.prediction.max_distance_mm == b.prediction.max_distance_mm;
}

}  // namespace cb
