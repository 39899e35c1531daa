// What systemd and remote checks see of a running kiosk, wired in one place so `cloudbrush kiosk`
// and its soak and watchdog tests run the same code: READY=1 (with the first STATUS) after the
// first presented frame, STATUS=… on every screen change after that, WATCHDOG=1 from the frame
// loop's every iteration when the unit asks for a watchdog (WatchdogPinger: a hung loop stops the
// pings), the health tracker and <data dir>/health.json, STOPPING=1 at the end. Problems are
// reported through the `report` callback (stderr in the binary) and never stop the kiosk.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "app/kiosk/health_file_writer.h"
#include "app/kiosk/health_tracker.h"
#include "app/kiosk/sd_notifier.h"
#include "app/kiosk/watchdog_interval.h"
#include "app/kiosk/watchdog_pinger.h"
#include "drivers/core/clock.h"

namespace cb {

class PenSource;

class KioskService {
 public:
  // `clock` (the frame loop's) and `pen` (may be null) must outlive the service. No watchdog
  // pings without `watchdog`.
  KioskService(SdNotifier notifier, std::optional<WatchdogTimeout> watchdog, const Clock& clock,
               const std::string& data_dir, const PenSource* pen,
               std::function<void(const std::string&)> report);
  KioskService(const KioskService&) = delete;
  KioskService& operator=(const KioskService&) = delete;

  // FrameLoopOptions::each_iteration: health, READY after the first presented frame, the
  // watchdog ping when due, health.json when due.
  void onIteration(bool presented);
  // KioskSetup::on_status: sent once READY is (the first status goes with READY).
  void onStatus(const std::string& status);
  // KioskSetup::on_input.
  void onInput() { health_.onInput(); }
  // At the end of the run.
  void stopping();

  bool readySent() const { return ready_sent_; }
  long watchdogPings() const { return pinger_ ? pinger_->pingsSent() : 0; }
  const HealthTracker& health() const { return health_; }

 private:
  SdNotifier notifier_;
  std::optional<WatchdogPinger> pinger_;
  const PenSource* pen_;
  std::function<void(const std::string&)> report_;
  HealthTracker health_;
  HealthFileWriter health_file_;
  bool ready_sent_ = false;
  std::string status_ = "attract loop: waiting for a visitor";
};

}  // namespace cb
