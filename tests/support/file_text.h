// A whole file's bytes as a string, for tests that read what a command or a run wrote. Empty
// when the file cannot be read (the test's own checks then fail on what is missing).
#pragma once

#include <fstream>
#include <sstream>
#include <string>

namespace cb::test {

inline std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace cb::test
