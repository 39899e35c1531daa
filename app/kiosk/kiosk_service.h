// What systemd and remote checks see of a running kiosk, wired in one place so `cloudbrush kiosk`
// and its soak and watchdog tests run the same code: READY=1 (with the first STATUS) after the
// first presented frame, STATUS=… on every screen change after that, WATCHDOG=1 from the frame
// loop's every iteration when the unit asks for a watchdog (WatchdogPinger: a hung loop stops the
// pings), the health tracker and <data dir>/health.json (and the metrics file), STOPPING=1 at the
// end. A health file that cannot be written is reported when it starts failing (and when it
// works again) and becomes last_error. Problems are
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
  // KioskSetup::on_problem: a save, journal or other failure becomes health.json's last_error.
  void onProblem(const std::string& problem) { health_.setError(problem); }
  // KioskSetup::on_storage ("" : saving works).
  void onStorage(const std::string& problem) { health_.setStorage(problem); }
  // The kiosk screen's counts, for the health file and the metrics (every iteration is fine).
  void setCounts(KioskCounts counts) { health_.setCounts(std::move(counts)); }
  // [monitoring] metrics_dir: the metrics file goes there with health.json.
  void setMetricsDir(const std::string& dir) { health_file_.setMetricsDir(dir); }
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
  std::string health_file_error_;  // the last failure to write it, reported once
  std::string status_ = "attract loop: waiting for a visitor";
};

}  // namespace cb
