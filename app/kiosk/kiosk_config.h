// The exhibition kiosk's settings (config/kiosk.toml): visitor language and idle times, the
// attract loop, the operator panel's key combination and PIN, the gallery and how long journals
// are kept. Every key is optional; a missing file gives the defaults below.
#pragma once

#include <cstdint>
#include <string>

namespace cb {

struct KioskConfig {
  // [visitor]
  std::string language = "en";    // a table of config/kiosk/texts.toml
  double idle_seconds = 90.0;     // no input this long: the visitor's cloud is cleared
  double warning_seconds = 10.0;  // the countdown shown before that
  // [attract]
  std::string attract_journal = "kiosk/attract.cbj";  // relative to the config dir, or absolute
  float orbit_degrees_per_second = 6.0f;
  double attract_hold_seconds = 10.0;  // the finished cloud orbits this long, then it replays
  double attract_speed = 1.0;          // journal time per clock time
  // [operator]
  std::string operator_keys = "ctrl+alt+o";  // then the PIN's digits
  // The PIN is no setting: it is kept hashed in the data dir (app/kiosk/operator_pin.h).
  // [gallery]
  bool gallery_enabled = false;
  uint64_t gallery_quota_bytes = 2000ull << 20;
  double gallery_keep_days = 30.0;
  // The floor of free space on the data dir's file system (statvfs): the oldest entries go to
  // keep it, and nothing is saved (the operator panel, health.json and the log say so) while
  // even an empty gallery cannot keep it. Journals are not started below it either.
  uint64_t min_free_bytes = 256ull << 20;
  // [journals]
  double journal_keep_days = 30.0;
  // [monitoring]
  // A folder for node_exporter's textfile collector: <dir>/cloudbrush.prom is replaced there
  // with the health file (app/kiosk/metrics_text.h). Empty: no metrics file.
  std::string metrics_dir;
};

// Throws std::runtime_error("FILE: section.key what") for a syntax error, a wrong type or a
// value out of range.
// Keys missing from the file keep their value in `base` (so /etc/cloudbrush/kiosk.toml is read
// over the shipped one, key by key).
KioskConfig loadKioskConfig(const std::string& path, KioskConfig base = {});

}  // namespace cb
