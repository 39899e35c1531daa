// Reads a TOML settings file; a syntax error becomes std::runtime_error("FILE:LINE: what").
#pragma once

#include <string>

#include <toml++/toml.h>

namespace cb {

toml::table parseTomlFileOrThrow(const std::string& path);

}  // namespace cb
