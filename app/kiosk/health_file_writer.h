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

  // Writes if the interval has passed since the last write (the first call writes).
  bool writeIfDue(std::string* error);
  // Writes now: creates the data directory if missing, measures its disk space (a failure there
  // leaves the disk fields null and is not an error), replaces health.json. False with *error
  // naming the path when the directory cannot be created or the file cannot be written.
  bool write(std::string* error);

 private:
  std::string data_dir_;
  const HealthTracker& tracker_;
  const Clock& clock_;
  int64_t interval_ns_;
  std::function<int64_t()> wall_clock_;
  bool written_ = false;
  int64_t last_write_ns_ = 0;
};

}  // namespace cb
