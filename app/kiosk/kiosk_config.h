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
  std::string operator_pin = "2468";         // 4..12 digits
  // [gallery]
  bool gallery_enabled = false;
  uint64_t gallery_quota_bytes = 2000ull << 20;
  double gallery_keep_days = 30.0;
  // [journals]
  double journal_keep_days = 30.0;
};

// Throws std::runtime_error("FILE: section.key what") for a syntax error, a wrong type or a
// value out of range.
KioskConfig loadKioskConfig(const std::string& path);

}  // namespace cb
