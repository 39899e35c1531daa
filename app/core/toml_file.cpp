#include "app/core/toml_file.h"

#include <stdexcept>

namespace cb {

toml::table parseTomlFileOrThrow(const std::string& path) {
  try {
    return toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    throw std::runtime_error(path + ":" + std::to_string(e.source().begin.line) + ": " +
                             std::string(e.description()));
  }
}

toml::table parseTomlTextOrThrow(std::string_view text, const std::string& name) {
  try {
    return toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    throw std::runtime_error(name + ":" + std::to_string(e.source().begin.line) + ": " +
                             std::string(e.description()));
  }
}

}  // namespace cb
