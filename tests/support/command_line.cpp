#include "tests/support/command_line.h"

#include <cstdio>
#include <exception>
#include <stdexcept>

namespace cb::test {

bool parseCommandLine(const char* program, int argc, char** argv,
                      const std::vector<CommandOption>& options) {
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      const CommandOption* option = nullptr;
      for (const CommandOption& o : options)
        if (o.name == a) option = &o;
      if (!option) throw std::runtime_error("unknown option " + a);
      if (option->flag) {
        option->set("");
        continue;
      }
      if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
      option->set(argv[++i]);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", program, e.what());
    return false;
  }
  return true;
}

void parseSizeOption(const std::string& option, const std::string& value, int* width, int* height) {
  if (std::sscanf(value.c_str(), "%dx%d", width, height) != 2)
    throw std::runtime_error(option + ": expected WxH, got '" + value + "'");
}

int runReportingErrors(const char* program, const std::function<int()>& body) {
  try {
    return body();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", program, e.what());
    return 1;
  }
}

}  // namespace cb::test
