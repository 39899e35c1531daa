// Keeps systemd's service watchdog fed from the frame loop: call tick() once per frame; it sends
// WATCHDOG=1 when at least the ping interval (half of WatchdogSec=) has passed on the injected
// clock since the last ping. A frame loop that hangs stops calling tick(), the pings stop, and
// systemd restarts the service — so the pinger must never run on a thread of its own.
#pragma once

#include <cstdint>
#include <string>

#include "app/kiosk/sd_notifier.h"
#include "app/kiosk/watchdog_interval.h"
#include "drivers/core/clock.h"

namespace cb {

class WatchdogPinger {
 public:
  // `notifier` and `clock` must outlive the pinger. The first tick() pings.
  WatchdogPinger(const SdNotifier& notifier, const Clock& clock, WatchdogTimeout timeout);

  // Pings if due. False with *error when the ping was due but could not be sent (the next tick
  // tries again).
  bool tick(std::string* error);

  int64_t pingIntervalNs() const { return interval_ns_; }
  long pingsSent() const { return pings_sent_; }

 private:
  const SdNotifier& notifier_;
  const Clock& clock_;
  int64_t interval_ns_;
  bool pinged_ = false;
  int64_t last_ping_ns_ = 0;
  long pings_sent_ = 0;
};

}  // namespace cb
