#include "app/kiosk/kiosk_service.h"

#include "drivers/core/pen_source.h"

namespace cb {

KioskService::KioskService(SdNotifier notifier, std::optional<WatchdogTimeout> watchdog,
                           const Clock& clock, const std::string& data_dir, const PenSource* pen,
                           std::function<void(const std::string&)> report)
    : notifier_(std::move(notifier)),
      pen_(pen),
      report_(std::move(report)),
      health_(clock),
      health_file_(data_dir, health_, clock) {
  if (watchdog) pinger_.emplace(notifier_, clock, *watchdog);
  health_.setDeviceState(pen_ ? pen_->backendName() : "no tablet backend");
}

void KioskService::onIteration(bool presented) {
  std::string error;
  if (presented) health_.onFrame();
  if (pen_)
    health_.setDeviceState(std::string(pen_->backendName()) + " " +
                           penConnectionName(pen_->connection()));
  if (presented && !ready_sent_) {
    ready_sent_ = true;
    if (!notifier_.ready(&error) || !notifier_.status(status_, &error)) report_(error);
  }
  if (pinger_ && !pinger_->tick(&error)) report_("watchdog: " + error);
  if (!health_file_.writeIfDue(&error)) {
    if (error != health_file_error_) report_("health file NOT WRITTEN: " + error);
    health_file_error_ = error;
    health_.setError("health file: " + error);
  } else if (!health_file_error_.empty()) {
    report_("health file written again: " + health_file_.path());
    health_file_error_.clear();
  }
}

void KioskService::onStatus(const std::string& status) {
  status_ = status;
  std::string error;
  if (ready_sent_ && !notifier_.status(status, &error)) report_(error);
}

void KioskService::stopping() {
  std::string error;
  // The final figures (a stopped kiosk's last health and metrics are its whole run's).
  if (!health_file_.write(&error)) report_("health file NOT WRITTEN: " + error);
  error.clear();
  if (!notifier_.stopping(&error)) report_(error);
}

}  // namespace cb
