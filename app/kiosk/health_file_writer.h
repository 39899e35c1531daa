// Writes the kiosk's health status as <data dir>/health.json, atomically (readers never see a
// half-written file), at most once per interval on the injected clock.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "app/kiosk/health_tracker.h"
#include "drivers/core/clock.h"

namespace cb {

class HealthFileWriter {
 public:
  static constexpr const char* kFileName = "health.json";

  // `tracker` and `clock` must outlive the writer. `wall_clock` gives Unix seconds (defaults to
  // the system clock; tests inject a fixed one).
  HealthFileWriter(std::string data_dir, const HealthTracker& tracker, const Clock& clock,
                   int64_t interval_ns = 5'000'000'000,
                   std::function<int64_t()> wall_clock = nullptr);

  std::string path() const;
  // Also replace <dir>/cloudbrush.prom (metrics_text.h) at each write; "" (the default): none.
  void setMetricsDir(std::string dir) { metrics_dir_ = std::move(dir); }
  std::string metricsPath() const;

  // Writes if the interval has passed since the last attempt (the first call writes; a failed
  // write is tried again an interval later, not at every frame). Until then it answers as the
  // last attempt did (false with the same *error).
  bool writeIfDue(std::string* error);
  // Writes now: creates the data directory if missing, measures its disk space (a failure there
  // leaves the disk fields null and is not an error), replaces health.json. False with *error
  // naming the path when the directory cannot be created or a file cannot be written (the
  // metrics file is written even when health.json is not).
  bool write(std::string* error);

 private:
  std::string data_dir_;
  std::string metrics_dir_;
  const HealthTracker& tracker_;
  const Clock& clock_;
  int64_t interval_ns_;
  std::function<int64_t()> wall_clock_;
  bool written_ = false;    // attempted at least once
  std::string last_error_;  // of the last writeIfDue() attempt
  int64_t last_write_ns_ = 0;
};

}  // namespace cb
