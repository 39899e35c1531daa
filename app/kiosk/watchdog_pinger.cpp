#include "app/kiosk/watchdog_pinger.h"

namespace cb {

WatchdogPinger::WatchdogPinger(const SdNotifier& notifier, const Clock& clock,
                               WatchdogTimeout timeout)
    : notifier_(notifier), clock_(clock), interval_ns_(timeout.pingIntervalNs()) {}

bool WatchdogPinger::tick(std::string* error) {
  const int64_t now = clock_.nowNs();
  if (pinged_ && now - last_ping_ns_ < interval_ns_) return true;
  if (!notifier_.watchdog(error)) return false;
  pinged_ = true;
  last_ping_ns_ = now;
  ++pings_sent_;
  return true;
}

}  // namespace cb
