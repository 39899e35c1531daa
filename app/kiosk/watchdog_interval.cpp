#include "app/kiosk/watchdog_interval.h"

#include <unistd.h>

#include <charconv>
#include <cstdlib>
#include <cstring>

namespace cb {

namespace {

// A positive decimal integer filling the whole string, or nullopt.
std::optional<int64_t> parsePositive(const char* text) {
  const char* end = text + std::strlen(text);
  int64_t value = 0;
  auto [ptr, ec] = std::from_chars(text, end, value);
  if (ec != std::errc() || ptr != end || ptr == text || value <= 0) return std::nullopt;
  return value;
}

}  // namespace

std::optional<WatchdogTimeout> parseWatchdogTimeout(const char* watchdog_usec,
                                                    const char* watchdog_pid, long own_pid,
                                                    std::string* error) {
  if (watchdog_usec == nullptr) return std::nullopt;
  if (watchdog_pid != nullptr) {
    std::optional<int64_t> pid = parsePositive(watchdog_pid);
    if (!pid) {
      if (error) *error = std::string("WATCHDOG_PID='") + watchdog_pid + "' is not a process id";
      return std::nullopt;
    }
    if (*pid != own_pid) return std::nullopt;  // meant for another process (e.g. our parent)
  }
  std::optional<int64_t> usec = parsePositive(watchdog_usec);
  constexpr int64_t kMaxUsec = INT64_MAX / 1000;
  if (!usec || *usec > kMaxUsec) {
    if (error)
      *error = std::string("WATCHDOG_USEC='") + watchdog_usec +
               "' is not a positive number of microseconds";
    return std::nullopt;
  }
  return WatchdogTimeout{*usec * 1000};
}

std::optional<WatchdogTimeout> watchdogTimeoutFromEnvironment(std::string* error) {
  return parseWatchdogTimeout(std::getenv("WATCHDOG_USEC"), std::getenv("WATCHDOG_PID"),
                              static_cast<long>(::getpid()), error);
}

}  // namespace cb
