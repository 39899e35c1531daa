// Reads a TOML settings file; a syntax error becomes std::runtime_error("FILE:LINE: what").
#pragma once

#include <string>
#include <string_view>

#include <toml++/toml.h>

namespace cb {

toml::table parseTomlFileOrThrow(const std::string& path);
// The same for TOML text held in memory; `name` stands for the file in messages.
toml::table parseTomlTextOrThrow(std::string_view text, const std::string& name);

}  // namespace cb
