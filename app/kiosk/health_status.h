// What a remote check wants to know about a running kiosk, and its JSON form (the health file).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace cb {

// What the kiosk screen counts (the health file and the metrics carry them).
struct KioskCounts {
  long visits = 0;
  long strokes = 0;                 // strokes mapped by all visitors
  long gallery_saved = 0;           // visitors' clouds kept in the gallery
  long saves_failed = 0;            // gallery entries and journals that could not be written
  std::string screen = "starting";  // attract, visitor, reconnect, operator, calibrate, error
};

struct HealthStatus {
  int64_t written_unix_s = 0;      // wall clock when the status was taken (staleness checks)
  double uptime_s = 0.0;           // since the kiosk started
  double frames_per_second = 0.0;  // over the last completed measuring window
  std::optional<double> last_input_age_s;   // since the last pen or key input; none yet: null
  std::string device_state;                 // e.g. "connected: Wacom Intuos4 M", "no tablet"
  std::optional<uint64_t> disk_free_bytes;  // on the data directory's file system; unknown: null
  std::optional<uint64_t> disk_total_bytes;
  std::string last_error;  // empty: none (null in JSON)
  // "ok" while saving works, else what is not saved and why (the disk is full, ...).
  std::string storage = "ok";
  long frames = 0;  // presented since the start
  KioskCounts counts;
};

// One JSON object on one line, keys in the order of the struct (the counts' flattened), strings
// escaped (control characters as \u00XX), non-finite numbers as null.
std::string healthStatusJson(const HealthStatus& status);

}  // namespace cb
