// One list of a config file's fields, read and written from the same rows: where a field lives
// (section, key), the member that holds it and the range a number must fall in. Each config keeps
// its own reader (brush.toml gathers errors, mapping.toml stops at the first, render.toml warns
// about its newer settings) but none names a field twice; the writer is shared: the text a journal
// records (floats with 9 significant digits, so the readers give back the same bits).
#pragma once

#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <variant>

#include <glm/glm.hpp>

namespace cb {

// The member a field reads into and writes from.
using FieldRef = std::variant<float*, int*, uint32_t*, bool*, glm::vec3*, glm::vec4*>;

template <class Config>
struct ConfigField {
  const char* section;  // the TOML table ("" for the top level, "style.ink" for a sub-table)
  const char* key;
  FieldRef (*at)(Config&);
  double lo = 0.0, hi = 0.0;  // the accepted range of a number (of each number of a vector)
};

// `key = value` (numbers "%.9g", vectors "[a, b, c]", flags true/false) and a newline.
inline void appendField(std::string& o, const char* key, const FieldRef& value) {
  char buf[64];
  o += std::string(key) + " = ";
  auto vec = [&](const float* v, int n) {
    o += "[";
    for (int i = 0; i < n; ++i) {
      std::snprintf(buf, sizeof buf, "%s%.9g", i ? ", " : "", double(v[i]));
      o += buf;
    }
    o += "]";
  };
  std::visit(
      [&](auto* v) {
        using T = std::remove_pointer_t<decltype(v)>;
        if constexpr (std::is_same_v<T, float>) {
          std::snprintf(buf, sizeof buf, "%.9g", double(*v));
          o += buf;
        } else if constexpr (std::is_same_v<T, bool>) {
          o += *v ? "true" : "false";
        } else if constexpr (std::is_same_v<T, glm::vec3> || std::is_same_v<T, glm::vec4>) {
          vec(&v->x, T::length());
        } else {
          o += std::to_string(*v);
        }
      },
      value);
  o += "\n";
}

// Every field of `fields` in `section`, in the list's order.
template <class Config>
void appendSection(std::string& o, std::span<const ConfigField<Config>> fields,
                   const Config& config, std::string_view section) {
  // `at` hands out a mutable member for the readers; the writer only reads through it.
  Config& c = const_cast<Config&>(config);
  for (const ConfigField<Config>& f : fields)
    if (section == f.section) appendField(o, f.key, f.at(c));
}

// Every field of `fields` in order, each section opened by "\n[section]\n" where it changes.
template <class Config>
void appendSections(std::string& o, std::span<const ConfigField<Config>> fields,
                    const Config& config) {
  Config& c = const_cast<Config&>(config);
  std::string_view open;
  for (const ConfigField<Config>& f : fields) {
    if (f.section != open) {
      open = f.section;
      o += "\n[" + std::string(open) + "]\n";
    }
    appendField(o, f.key, f.at(c));
  }
}

}  // namespace cb
