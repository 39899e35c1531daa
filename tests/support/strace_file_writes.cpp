#include "tests/support/strace_file_writes.h"

#include <sstream>

namespace cb::test {

FileWrites fileWritesOutside(const std::string& trace, const std::string& cwd,
                             const std::vector<std::string>& allowed) {
  FileWrites result;
  std::istringstream lines(trace);
  std::string line;
  const auto has = [&line](const char* word) { return line.find(word) != std::string::npos; };
  while (std::getline(lines, line)) {
    const bool writing = (has("open") && (has("O_WRONLY") || has("O_RDWR") || has("O_CREAT"))) ||
                         has("mkdir") || has("rename") || has("unlink") || has("rmdir");
    if (!writing || has("= -1")) continue;
    const size_t q = line.find('"');
    if (q == std::string::npos) continue;
    std::string path = line.substr(q + 1, line.find('"', q + 1) - q - 1);
    if (path.rfind("/dev/", 0) == 0) continue;
    ++result.writes;
    if (path.empty() || path[0] != '/') path = cwd + "/" + path;
    bool inside = false;
    for (const std::string& dir : allowed)
      inside = inside || path == dir || path.rfind(dir + "/", 0) == 0;
    if (!inside) result.outside.push_back(line);
  }
  return result;
}

}  // namespace cb::test
