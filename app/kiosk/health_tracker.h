// Collects what the health file reports while the kiosk runs: the frame loop calls onFrame(),
// input handling onInput(), the device layer setDeviceState(), anything that fails setError().
// All times come from the injected clock, so tests drive it by hand.
#pragma once

#include <cstdint>
#include <string>

#include "app/kiosk/disk_space.h"
#include "app/kiosk/health_status.h"
#include "drivers/core/clock.h"

namespace cb {

class HealthTracker {
 public:
  // Uptime counts from construction. Frame rate is measured over windows of `fps_window_ns`.
  explicit HealthTracker(const Clock& clock, int64_t fps_window_ns = 1'000'000'000);

  void onFrame();
  void onInput();
  void setDeviceState(std::string state) { device_state_ = std::move(state); }
  void setError(std::string error) { last_error_ = std::move(error); }
  // "" or "ok": saving works; else what is not saved and why.
  void setStorage(std::string problem) { storage_ = problem.empty() ? "ok" : std::move(problem); }
  void setCounts(KioskCounts counts) { counts_ = std::move(counts); }
  long frames() const { return frames_; }

  // The status now. `disk` null: the disk fields are null; `wall_unix_s` is copied as is.
  HealthStatus snapshot(const DiskSpace* disk, int64_t wall_unix_s) const;

 private:
  const Clock& clock_;
  int64_t fps_window_ns_;
  int64_t start_ns_;
  int64_t window_start_ns_;
  long window_frames_ = 0;
  double frames_per_second_ = 0.0;
  bool have_input_ = false;
  int64_t last_input_ns_ = 0;
  std::string device_state_ = "unknown";
  std::string last_error_;
  std::string storage_ = "ok";
  long frames_ = 0;
  KioskCounts counts_;
};

}  // namespace cb
