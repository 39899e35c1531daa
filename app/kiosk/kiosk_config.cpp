#include "app/kiosk/kiosk_config.h"

#include <cctype>
#include <stdexcept>

#include <toml++/toml.h>

#include "app/core/toml_file.h"

namespace cb {
namespace {

[[noreturn]] void bad(const std::string& path, const std::string& key, const std::string& what,
                      toml::node_view<const toml::node> node = {}) {
  const std::string line = node && node.node()->source().begin.line > 0
                               ? ":" + std::to_string(node.node()->source().begin.line)
                               : "";
  throw std::runtime_error(path + line + ": " + key + " " + what);
}

void readNumber(const toml::table& root, const std::string& path, const char* section,
                const char* key, double lo, double hi, double* out) {
  auto node = root[section][key];
  if (!node) return;
  const std::string name = std::string(section) + "." + key;
  auto v = node.value<double>();
  if (!node.is_number() || !v) bad(path, name, "must be a number", node);
  if (*v < lo || *v > hi)
    bad(path, name, "must be between " + std::to_string(lo) + " and " + std::to_string(hi), node);
  *out = *v;
}

void readString(const toml::table& root, const std::string& path, const char* section,
                const char* key, std::string* out) {
  auto node = root[section][key];
  if (!node) return;
  auto v = node.value<std::string>();
  if (!node.is_string() || !v)
    bad(path, std::string(section) + "." + key, "must be a string", node);
  *out = *v;
}

}  // namespace

KioskConfig loadKioskConfig(const std::string& path, KioskConfig base) {
  const toml::table root = parseTomlFileOrThrow(path);
  KioskConfig c = std::move(base);
  readString(root, path, "visitor", "language", &c.language);
  readNumber(root, path, "visitor", "idle_seconds", 0.1, 86400.0, &c.idle_seconds);
  readNumber(root, path, "visitor", "warning_seconds", 0.0, 3600.0, &c.warning_seconds);
  readString(root, path, "attract", "journal", &c.attract_journal);
  double orbit = c.orbit_degrees_per_second;
  readNumber(root, path, "attract", "orbit_degrees_per_second", -90.0, 90.0, &orbit);
  c.orbit_degrees_per_second = float(orbit);
  readNumber(root, path, "attract", "hold_seconds", 0.0, 3600.0, &c.attract_hold_seconds);
  readNumber(root, path, "attract", "speed", 0.05, 100.0, &c.attract_speed);
  readString(root, path, "operator", "keys", &c.operator_keys);
  if (auto node = root["operator"]["pin"])
    bad(path, "operator.pin",
        "is not read: the PIN is kept hashed in the data dir; remove this line and set the PIN "
        "at the kiosk (the operator key combination asks for one) or with `cloudbrush kiosk "
        "--set-pin`",
        node);
  if (auto node = root["gallery"]["enabled"]) {
    if (!node.is_boolean()) bad(path, "gallery.enabled", "must be true or false", node);
    c.gallery_enabled = *node.value<bool>();
  }
  double quota_mb = double(c.gallery_quota_bytes >> 20);
  readNumber(root, path, "gallery", "quota_mb", 1.0, 1e7, &quota_mb);
  c.gallery_quota_bytes = uint64_t(quota_mb * 1048576.0);
  readNumber(root, path, "gallery", "keep_days", 0.0, 36500.0, &c.gallery_keep_days);
  double min_free_mb = double(c.min_free_bytes >> 20);
  readNumber(root, path, "gallery", "min_free_mb", 0.0, 1e7, &min_free_mb);
  c.min_free_bytes = uint64_t(min_free_mb * 1048576.0);
  readString(root, path, "monitoring", "metrics_dir", &c.metrics_dir);
  readNumber(root, path, "journals", "keep_days", 0.0, 36500.0, &c.journal_keep_days);
  if (c.warning_seconds >= c.idle_seconds)
    bad(path, "visitor.warning_seconds", "must be less than visitor.idle_seconds");
  return c;
}

}  // namespace cb
