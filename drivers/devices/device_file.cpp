#include "drivers/devices/device_file.h"

#include <toml++/toml.h>
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <set>
#include "drivers/core/toml_number.h"

namespace cb {
namespace {

constexpr size_t kMaxFileBytes = 1 << 20;  // device files are a few KiB

std::string where(const std::string& file, const toml::source_region& r) {
  return file + ":" + std::to_string(r.begin.line) + ":" + std::to_string(r.begin.column);
}

// Reads one file's tables, collecting FILE:LINE:COL errors.
class Reader {
 public:
  Reader(std::string file, std::vector<std::string>* errors)
      : file_(std::move(file)), errors_(errors) {}
  bool ok() const { return ok_; }
  const std::string& file() const { return file_; }

  void fail(const toml::source_region& r, const std::string& key, const std::string& what) {
    errors_->push_back(where(file_, r) + ": " + key + ": " + what);
    ok_ = false;
  }
  // Keys of `t` that are not in `allowed` are mistakes (a misspelt quirk must not pass silently).
  void onlyKeys(const toml::table& t, const std::string& prefix,
                std::initializer_list<const char*> allowed) {
    for (const auto& kv : t) {
      const toml::key& k = kv.first;  // (clang 14 cannot capture a structured binding)
      const bool known =
          std::any_of(allowed.begin(), allowed.end(), [&](const char* a) { return k.str() == a; });
      if (!known) {
        std::string list;
        for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
        fail(k.source(), prefix + std::string(k.str()),
             "unknown key (expected one of: " + list + ")");
      }
    }
  }
  const toml::table* table(const toml::table& t, const char* key, const std::string& prefix,
                           const toml::source_region& parent, bool required) {
    const toml::node* n = t.get(key);
    if (!n) {
      if (required) fail(parent, prefix + key, "missing");
      return nullptr;
    }
    if (!n->is_table()) {
      fail(n->source(), prefix + key, "expected a table");
      return nullptr;
    }
    return n->as_table();
  }
  std::optional<int64_t> integer(const toml::table& t, const char* key, const std::string& prefix,
                                 const toml::source_region& parent, int64_t lo, int64_t hi,
                                 bool required) {
    const toml::node* n = t.get(key);
    if (!n) {
      if (required) fail(parent, prefix + key, "missing");
      return std::nullopt;
    }
    std::optional<int64_t> v = n->value_exact<int64_t>();
    if (!v) {
      fail(n->source(), prefix + key, "expected an integer");
      return std::nullopt;
    }
    if (*v < lo || *v > hi) {
      fail(n->source(), prefix + key,
           std::to_string(*v) + " is outside " + std::to_string(lo) + ".." + std::to_string(hi));
      return std::nullopt;
    }
    return v;
  }
  std::optional<double> number(const toml::table& t, const char* key, const std::string& prefix,
                               const toml::source_region& parent, double lo, double hi) {
    const toml::node* n = t.get(key);
    if (!n) {
      fail(parent, prefix + key, "missing");
      return std::nullopt;
    }
    // Integers too; NaN and infinities refused before any comparison.
    const std::optional<double> v =
        toml_number::numberIn(*n, {}, prefix + key, -DBL_MAX, DBL_MAX, nullptr);
    if (!v) {
      fail(n->source(), prefix + key, "expected a number");
      return std::nullopt;
    }
    if (*v < lo || *v > hi) {
      fail(n->source(), prefix + key,
           std::to_string(*v) + " is outside " + std::to_string(lo) + ".." + std::to_string(hi));
      return std::nullopt;
    }
    return v;
  }
  std::optional<std::string> text(const toml::table& t, const char* key, const std::string& prefix,
                                  const toml::source_region& parent, bool required) {
    const toml::node* n = t.get(key);
    if (!n) {
      if (required) fail(parent, prefix + key, "missing");
      return std::nullopt;
    }
    std::optional<std::string> v = n->value_exact<std::string>();
    if (!v || v->empty()) {
      fail(n->source(), prefix + key, "expected a non-empty string");
      return std::nullopt;
    }
    return v;
  }
  // An array of integers in lo..hi.
  std::optional<std::vector<int64_t>> integers(const toml::table& t, const char* key,
                                               const std::string& prefix,
                                               const toml::source_region& parent, int64_t lo,
                                               int64_t hi, bool required) {
    const toml::node* n = t.get(key);
    if (!n) {
      if (required) fail(parent, prefix + key, "missing");
      return std::nullopt;
    }
    const toml::array* a = n->as_array();
    if (!a) {
      fail(n->source(), prefix + key, "expected an array of integers");
      return std::nullopt;
    }
    std::vector<int64_t> out;
    for (const toml::node& e : *a) {
      std::optional<int64_t> v = e.value_exact<int64_t>();
      if (!v || *v < lo || *v > hi) {
        fail(e.source(), prefix + key,
             "expected integers in " + std::to_string(lo) + ".." + std::to_string(hi));
        return std::nullopt;
      }
      out.push_back(*v);
    }
    return out;
  }

 private:
  std::string file_;
  std::vector<std::string>* errors_;
  bool ok_ = true;
};

struct ParsedFile {
  std::string name;
  toml::table root;
};

void readToolTables(Reader& r, const toml::table& root,
                    std::vector<std::shared_ptr<ToolTable>>& out) {
  const toml::node* n = root.get("tool_table");
  if (!n) return;
  if (!n->is_table()) {
    r.fail(n->source(), "tool_table", "expected tables [tool_table.NAME]");
    return;
  }
  for (const auto& [name, node] : *n->as_table()) {
    const std::string prefix = "tool_table." + std::string(name.str()) + ".";
    const toml::table* t = node.as_table();
    if (!t) {
      r.fail(node.source(), prefix.substr(0, prefix.size() - 1), "expected a table");
      continue;
    }
    r.onlyKeys(*t, prefix, {"eraser", "mouse", "lens"});
    auto table = std::make_shared<ToolTable>();
    table->name = std::string(name.str());
    for (auto [key, kind] :
         {std::pair{"eraser", ToolKind::kEraser}, std::pair{"mouse", ToolKind::kMouse},
          std::pair{"lens", ToolKind::kLens}}) {
      auto ids = r.integers(*t, key, prefix, t->source(), 0, 0xFFFFFFFF, false);
      if (!ids) continue;
      for (int64_t id : *ids) {
        auto [it, added] = table->ids.emplace(static_cast<uint32_t>(id), kind);
        if (!added && it->second != kind) {
          char hex[16];
          std::snprintf(hex, sizeof hex, "%#x", static_cast<unsigned>(id));
          r.fail(t->get(key)->source(), prefix + key,
                 std::string("tool id ") + hex + " is listed under two kinds");
        }
      }
    }
    out.push_back(std::move(table));
  }
}

// The family's identity: name, vendor, driver rules, protocol, tool table, idle timeout.
void readFamilyIdentity(Reader& r, const toml::table* f, const DeviceDatabase& db,
                        DeviceEntry& base) {
  const toml::source_region& fs = f->source();
  if (auto v = r.text(*f, "name", "family.", fs, true)) base.family = *v;
  if (auto v = r.integer(*f, "vendor", "family.", fs, 0, 0xFFFF, true))
    base.vendor = static_cast<uint16_t>(*v);
  if (auto v = r.text(*f, "driver", "family.", fs, true)) {
    if (*v == "wacom")
      base.rules = PenDriverRules::kWacom;
    else if (*v == "hid-generic")
      base.rules = PenDriverRules::kHidInput;
    else
      r.fail(f->get("driver")->source(), "family.driver",
             "\"" + *v + "\": expected \"wacom\" or \"hid-generic\"");
  }
  if (auto v = r.text(*f, "protocol", "family.", fs, true)) {
    if (*v == "intuos4")
      base.protocol = PenProtocol::kIntuos4;
    else if (*v == "descriptor")
      base.protocol = PenProtocol::kDescriptor;
    else
      r.fail(f->get("protocol")->source(), "family.protocol",
             "\"" + *v + "\": expected \"intuos4\" or \"descriptor\"");
  }
  if (auto v = r.text(*f, "tool_table", "family.", fs, false)) {
    base.tools = db.toolTable(*v);
    if (!base.tools)
      r.fail(f->get("tool_table")->source(), "family.tool_table",
             "no [tool_table." + *v + "] in any device file");
  }
  if (auto v = r.integer(*f, "idle_proximity_timeout_ms", "family.", fs, 0, 10000, false))
    base.idle_proximity_timeout_ms = static_cast<int>(*v);
}

// The Intuos4 mode switch and the input core's fuzz per axis.
void readModeSwitchAndFuzz(Reader& r, const toml::table* f, DeviceEntry& base) {
  const toml::source_region& fs = f->source();
  if (const toml::table* m = r.table(*f, "mode_switch", "family.", fs, false)) {
    r.onlyKeys(*m, "family.mode_switch.", {"feature_report", "value"});
    if (auto v = r.integer(*m, "feature_report", "family.mode_switch.", m->source(), 1, 255, true))
      base.mode_report_id = static_cast<uint8_t>(*v);
    if (auto v = r.integer(*m, "value", "family.mode_switch.", m->source(), 0, 255, true))
      base.mode_value = static_cast<uint8_t>(*v);
  }
  if (const toml::table* z = r.table(*f, "fuzz", "family.", fs, false)) {
    r.onlyKeys(*z, "family.fuzz.", {"position", "tilt", "distance", "pressure"});
    const auto get = [&](const char* key, int32_t& to) {
      if (auto v = r.integer(*z, key, "family.fuzz.", z->source(), 0, 1 << 16, false))
        to = static_cast<int32_t>(*v);
    };
    get("position", base.fuzz.position);
    get("tilt", base.fuzz.tilt);
    get("distance", base.fuzz.distance);
    get("pressure", base.fuzz.pressure);
  }
}

// The Intuos4 protocol's ranges (a descriptor gives its own).
void readIntuos4Ranges(Reader& r, const toml::table* f, DeviceEntry& base) {
  const toml::source_region& fs = f->source();
  const toml::table* ranges =
      r.table(*f, "ranges", "family.", fs, base.protocol == PenProtocol::kIntuos4);
  if (ranges && base.protocol != PenProtocol::kIntuos4)
    r.fail(ranges->source(), "family.ranges",
           "only for protocol \"intuos4\" (a descriptor gives its own ranges)");
  if (ranges && base.protocol == PenProtocol::kIntuos4) {
    const std::string p = "family.ranges.";
    const toml::source_region& rs = ranges->source();
    r.onlyKeys(*ranges, p,
               {"resolution_per_mm", "pressure_max", "tilt_min", "tilt_max", "tilt_per_radian",
                "distance_max"});
    PenDeviceInfo& d = base.info;
    if (auto v = r.number(*ranges, "resolution_per_mm", p, rs, 1e-3, 1e6)) d.x_res = d.y_res = *v;
    if (auto v = r.integer(*ranges, "pressure_max", p, rs, 1, 65535, true))
      d.pressure_max = static_cast<int32_t>(*v);
    auto tmin = r.integer(*ranges, "tilt_min", p, rs, -32768, 0, true);
    auto tmax = r.integer(*ranges, "tilt_max", p, rs, 1, 32767, true);
    if (tmin) d.tilt_min = static_cast<int32_t>(*tmin);
    if (tmax) d.tilt_max = static_cast<int32_t>(*tmax);
    // The kernel declares tilt resolution in units per radian; PenDeviceInfo holds per degree.
    if (auto v = r.number(*ranges, "tilt_per_radian", p, rs, 1e-3, 1e6))
      d.tilt_res = *v * M_PI / 180.0;
    if (auto v = r.integer(*ranges, "distance_max", p, rs, 0, 65535, true))
      d.distance_max = static_cast<int32_t>(*v);
  }
}

// Fix-ups belong to the whole family.
void readReportFixups(Reader& r, const toml::table& root, DeviceEntry& base) {
  // Fix-ups belong to the whole family.
  if (const toml::node* xn = root.get("report_fixup")) {
    const toml::array* xs = xn->as_array();
    if (!xs || !xs->is_array_of_tables()) {
      r.fail(xn->source(), "report_fixup", "expected [[report_fixup]] tables");
    } else {
      for (const toml::node& x : *xs) {
        const toml::table& t = *x.as_table();
        const std::string p = "report_fixup.";
        r.onlyKeys(t, p, {"size", "offset", "expect", "replace"});
        ReportFixup fx;
        fx.where = where(r.file(), t.source());
        if (auto v = r.integer(t, "size", p, t.source(), 0, 4096, false)) fx.size = size_t(*v);
        if (auto v = r.integer(t, "offset", p, t.source(), 0, 4095, true)) fx.offset = size_t(*v);
        auto e = r.integers(t, "expect", p, t.source(), 0, 255, true);
        auto s = r.integers(t, "replace", p, t.source(), 0, 255, true);
        if (!e || !s) continue;
        if (e->empty() || e->size() != s->size()) {
          const toml::node* replace = t.get("replace");
          r.fail(replace ? replace->source() : t.source(), p + "replace",
                 "must have as many bytes as expect (" + std::to_string(e->size()) + ")");
          continue;
        }
        if (fx.size != 0 && fx.offset + e->size() > fx.size) {
          // offset may be left out (0): then the table itself is where the problem is.
          const toml::node* offset = t.get("offset");
          r.fail(offset ? offset->source() : t.source(), p + "offset", "the bytes end past size");
          continue;
        }
        fx.expect.assign(e->begin(), e->end());
        fx.replace.assign(s->begin(), s->end());
        base.fixups.push_back(std::move(fx));
      }
    }
  }
}

// The family's models (or, for a descriptor family with none, every product of the vendor).
void readModels(Reader& r, const toml::table& root, const DeviceEntry& base,
                std::vector<DeviceEntry>& out) {
  const toml::source_region& fs = root.get("family")->source();
  const toml::node* mn = root.get("model");
  const toml::array* models = mn ? mn->as_array() : nullptr;
  if (mn && (!models || !models->is_array_of_tables())) {
    r.fail(mn->source(), "model", "expected [[model]] tables");
    return;
  }
  if (!models || models->empty()) {
    if (base.protocol == PenProtocol::kIntuos4)
      r.fail(fs, "model", "protocol \"intuos4\" needs at least one [[model]] with its size");
    else
      out.push_back(base);  // every product of the vendor
    return;
  }
  std::set<int64_t> seen;
  for (const toml::node& mnode : *models) {
    const toml::table& m = *mnode.as_table();
    const std::string p = "model.";
    r.onlyKeys(m, p, {"product", "name", "x_max", "y_max"});
    DeviceEntry e = base;
    e.where = where(r.file(), m.source());
    if (auto v = r.integer(m, "product", p, m.source(), 0, 0xFFFF, true)) {
      e.product = static_cast<uint16_t>(*v);
      if (!seen.insert(*v).second)
        r.fail(m.get("product")->source(), p + "product", "listed twice");
    }
    if (auto v = r.text(m, "name", p, m.source(), true)) e.name = *v;
    const bool sized = base.protocol == PenProtocol::kIntuos4;
    if (!sized && (m.get("x_max") || m.get("y_max")))
      r.fail(m.source(), p + "x_max",
             "only for protocol \"intuos4\" (a descriptor gives its own ranges)");
    if (sized) {
      if (auto v = r.integer(m, "x_max", p, m.source(), 1, 0x7FFFFFFF, true))
        e.info.x_max = static_cast<int32_t>(*v);
      if (auto v = r.integer(m, "y_max", p, m.source(), 1, 0x7FFFFFFF, true))
        e.info.y_max = static_cast<int32_t>(*v);
    }
    e.info.usb_vendor = e.vendor;
    e.info.usb_product = e.product.value_or(0);
    std::snprintf(e.info.name, sizeof e.info.name, "%s", e.name.c_str());
    out.push_back(std::move(e));
  }
}

// The family of one file and its models; appends entries when the whole file is sound.
void readFamily(Reader& r, const toml::table& root, const DeviceDatabase& db,
                std::vector<DeviceEntry>& out) {
  r.onlyKeys(root, "", {"family", "model", "report_fixup", "tool_table"});
  const toml::node* fn = root.get("family");
  if (!fn) {
    if (root.get("model") || root.get("report_fixup"))
      r.fail(root.source(), "family", "missing (models and fix-ups belong to a [family])");
    return;
  }
  const toml::table* f = fn->as_table();
  if (!f) {
    r.fail(fn->source(), "family", "expected a table");
    return;
  }
  r.onlyKeys(*f, "family.",
             {"name", "vendor", "driver", "protocol", "tool_table", "idle_proximity_timeout_ms",
              "mode_switch", "fuzz", "ranges"});
  DeviceEntry base;
  base.where = where(r.file(), f->source());
  readFamilyIdentity(r, f, db, base);
  readModeSwitchAndFuzz(r, f, base);
  readIntuos4Ranges(r, f, base);
  readReportFixups(r, root, base);
  readModels(r, root, base, out);
}

}  // namespace

DeviceFileLoad parseDeviceFiles(const std::vector<std::pair<std::string, std::string>>& files) {
  DeviceFileLoad result;
  auto db = std::make_shared<DeviceDatabase>();
  std::vector<ParsedFile> parsed;
  for (const auto& [name, text] : files) {
    try {
      parsed.push_back({name, toml::parse(text, name)});
    } catch (const toml::parse_error& e) {
      result.errors.push_back(where(name, e.source()) + ": " + std::string(e.description()));
    }
  }
  // Tool tables first: a family may name one from any file. A file whose tool tables have a
  // mistake adds no entry either, like a mistake anywhere else in it.
  std::vector<bool> tables_sound(parsed.size(), true);
  for (size_t i = 0; i < parsed.size(); ++i) {
    const ParsedFile& p = parsed[i];
    Reader r(p.name, &result.errors);
    std::vector<std::shared_ptr<ToolTable>> tables;
    readToolTables(r, p.root, tables);
    for (auto& t : tables) {
      if (!r.ok()) break;
      if (db->toolTable(t->name)) {
        r.fail(p.root.get("tool_table")->source(), "tool_table." + t->name, "defined in two files");
        break;
      }
      db->addToolTable(std::move(t));
    }
    tables_sound[i] = r.ok();
  }
  for (size_t i = 0; i < parsed.size(); ++i) {
    const ParsedFile& p = parsed[i];
    Reader r(p.name, &result.errors);
    std::vector<DeviceEntry> entries;
    readFamily(r, p.root, *db, entries);
    if (!r.ok() || !tables_sound[i]) continue;  // a file with a mistake adds no entry
    for (DeviceEntry& e : entries) {
      std::string clash;
      const std::string at = e.where;
      if (!db->add(std::move(e), &clash))
        result.errors.push_back(at + ": model: this USB id already has an entry at " + clash);
    }
    db->addFile(p.name);
  }
  result.database = std::move(db);
  return result;
}

DeviceFileLoad loadDeviceDirectory(const std::string& dir) {
  std::vector<std::pair<std::string, std::string>> files;
  std::vector<std::string> errors;
  std::error_code ec;
  std::vector<std::filesystem::path> paths;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec))
    if (e.path().extension() == ".toml") paths.push_back(e.path());
  if (ec) errors.push_back(dir + ": cannot list the device files: " + ec.message());
  std::sort(paths.begin(), paths.end());
  for (const auto& p : paths) {
    std::ifstream in(p, std::ios::binary);
    std::string text;
    if (in) {
      in.seekg(0, std::ios::end);
      const auto size = in.tellg();
      in.seekg(0);
      if (size < 0 || static_cast<size_t>(size) > kMaxFileBytes) {
        errors.push_back(p.string() + ": larger than 1 MiB; not a device file");
        continue;
      }
      text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    if (!in && !in.eof()) {
      errors.push_back(p.string() + ": cannot read");
      continue;
    }
    files.emplace_back(p.string(), std::move(text));
  }
  DeviceFileLoad load = parseDeviceFiles(files);
  errors.insert(errors.end(), load.errors.begin(), load.errors.end());
  load.errors = std::move(errors);
  return load;
}

}  // namespace cb
