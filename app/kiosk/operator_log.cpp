#include "app/kiosk/operator_log.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>

namespace cb {

bool OperatorLog::write(const std::string& action, std::string* error) const {
  char stamp[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  const std::string line = std::string(stamp) + " " + action + "\n";
  std::fprintf(stderr, "cloudbrush kiosk: operator: %s\n", action.c_str());
  std::FILE* file = std::fopen(path_.c_str(), "a");
  if (!file) {
    *error = path_ + ": " + std::strerror(errno);
    return false;
  }
  const bool ok = std::fputs(line.c_str(), file) >= 0;
  const bool closed = std::fclose(file) == 0;
  if (!ok || !closed) {
    *error = path_ + ": write failed: " + std::strerror(errno);
    return false;
  }
  return true;
}

}  // namespace cb
