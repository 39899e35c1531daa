// Running a command from a test: its exit status and everything it printed.
#pragma once

#include <string>

namespace cb::test {

struct CommandRun {
  int status = -1;  // exit status; -1 when the command did not exit (e.g. killed by a signal)
  std::string out;  // stdout and stderr together
};

CommandRun runCommand(const std::string& command);

}  // namespace cb::test
