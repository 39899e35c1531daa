// The command line of a test binary that is its own program (the kiosk's month and soak runs):
// options as a table, `--name VALUE` or a flag, parsed in one place; and its main()'s error
// reporting. Errors are printed as "PROGRAM: what".
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace cb::test {

struct CommandOption {
  std::string name;                             // "--days"
  std::function<void(const std::string&)> set;  // the option's value ("" for a flag)
  bool flag = false;                            // takes no value
};

// Parses argv[1..] against `options`. A missing value, an unknown option or what `set` threw
// (std::stoi's error, or a message of its own) is printed as "PROGRAM: what" on stderr and
// gives false (the caller exits with status 2).
bool parseCommandLine(const char* program, int argc, char** argv,
                      const std::vector<CommandOption>& options);

// "WxH" into *width and *height, else throws "OPTION: expected WxH, got 'VALUE'".
void parseSizeOption(const std::string& option, const std::string& value, int* width, int* height);

// Runs `body` (the program); an exception escaping it is printed as "PROGRAM: what" and gives
// status 1.
int runReportingErrors(const char* program, const std::function<int()>& body);

}  // namespace cb::test
