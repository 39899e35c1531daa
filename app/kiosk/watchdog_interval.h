// The service watchdog's timeout as systemd passes it: $WATCHDOG_USEC (microseconds, from the
// unit's WatchdogSec=) and $WATCHDOG_PID (the process it is meant for, if set).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace cb {

struct WatchdogTimeout {
  int64_t timeout_ns = 0;  // systemd restarts the service after this long without WATCHDOG=1
  // How often to ping: half the timeout, as sd_watchdog_enabled(3) recommends.
  int64_t pingIntervalNs() const { return timeout_ns / 2; }
};

// Parses the two variables' values (null when unset). nullopt without an error when no watchdog
// is asked for: WATCHDOG_USEC unset, or WATCHDOG_PID names another process than `own_pid`.
// nullopt with *error for a value that is not a positive decimal integer ("WATCHDOG_USEC='abc'
// is not a positive number of microseconds").
std::optional<WatchdogTimeout> parseWatchdogTimeout(const char* watchdog_usec,
                                                    const char* watchdog_pid, long own_pid,
                                                    std::string* error);

// parseWatchdogTimeout on this process's environment and pid.
std::optional<WatchdogTimeout> watchdogTimeoutFromEnvironment(std::string* error);

}  // namespace cb
