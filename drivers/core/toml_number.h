// Numbers from TOML read without undefined behaviour: toml++'s node::value<int64_t>() converts a
// float to an integer before any range check (1e40 or NaN into int64_t is undefined), so every
// config reader takes its numbers through these. Refusals name FILE:LINE: field: what.
// Header-only; include it only where toml++ is linked (calibration/, drivers/devices, app/).
#pragma once

#include <toml++/toml.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace cb::toml_number {

// "FILE:LINE: field: what" for a node (the file as toml++ recorded it when `file` is empty;
// "line LINE: field: what" when neither names one).
inline std::string where(const toml::node& node, std::string_view file, std::string_view field,
                         std::string_view what) {
  std::string f(file);
  if (f.empty() && node.source().path) f = *node.source().path;
  const std::string line = std::to_string(node.source().begin.line);
  return (f.empty() ? "line " + line : f + ":" + line) + ": " + std::string(field) + ": " +
         std::string(what);
}

// An integer in lo..hi. A float is taken only when it is finite, whole and in range (compared
// as a double before any conversion); anything else is refused with `*error` set.
inline std::optional<int64_t> integerIn(const toml::node& node, std::string_view file,
                                        std::string_view field, int64_t lo, int64_t hi,
                                        std::string* error) {
  const std::string range = std::to_string(lo) + ".." + std::to_string(hi);
  auto refuse = [&](const std::string& what) -> std::optional<int64_t> {
    if (error) *error = where(node, file, field, what);
    return std::nullopt;
  };
  if (const auto* i = node.as_integer()) {
    const int64_t v = i->get();
    if (v < lo || v > hi) return refuse(std::to_string(v) + " is outside " + range);
    return v;
  }
  if (const auto* f = node.as_floating_point()) {
    const double d = f->get();
    if (!std::isfinite(d) || d != std::floor(d)) return refuse("expected an integer in " + range);
    // lo and hi as doubles may round outward; the strict bounds keep the cast defined.
    if (d < static_cast<double>(lo) || d > static_cast<double>(hi) || d >= 0x1p63 || d < -0x1p63)
      return refuse("outside " + range);
    const auto v = static_cast<int64_t>(d);
    if (v < lo || v > hi) return refuse("outside " + range);
    return v;
  }
  return refuse("expected an integer in " + range);
}

// A finite number (integer or float) in lo..hi.
inline std::optional<double> numberIn(const toml::node& node, std::string_view file,
                                      std::string_view field, double lo, double hi,
                                      std::string* error) {
  auto refuse = [&](const std::string& what) -> std::optional<double> {
    if (error) *error = where(node, file, field, what);
    return std::nullopt;
  };
  double v = 0;
  if (const auto* i = node.as_integer())
    v = static_cast<double>(i->get());
  else if (const auto* f = node.as_floating_point())
    v = f->get();
  else
    return refuse("expected a number");
  if (!std::isfinite(v) || v < lo || v > hi)
    return refuse(std::to_string(v) + " is outside " + std::to_string(lo) + ".." +
                  std::to_string(hi));
  return v;
}

}  // namespace cb::toml_number
