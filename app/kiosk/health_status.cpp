#include "app/kiosk/health_status.h"

#include <cmath>
#include <cstdio>

#include "app/core/json_text.h"

namespace cb {

namespace {

std::string jsonNumber(double value) {
  if (!std::isfinite(value)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", value);
  return buf;
}

}  // namespace

std::string healthStatusJson(const HealthStatus& s) {
  std::string out = "{";
  out += "\"written_unix_s\":" + std::to_string(s.written_unix_s);
  out += ",\"uptime_s\":" + jsonNumber(s.uptime_s);
  out += ",\"frames_per_second\":" + jsonNumber(s.frames_per_second);
  out += ",\"last_input_age_s\":" +
         (s.last_input_age_s ? jsonNumber(*s.last_input_age_s) : std::string("null"));
  out += ",\"device_state\":" + jsonString(s.device_state);
  out += ",\"disk_free_bytes\":" +
         (s.disk_free_bytes ? std::to_string(*s.disk_free_bytes) : std::string("null"));
  out += ",\"disk_total_bytes\":" +
         (s.disk_total_bytes ? std::to_string(*s.disk_total_bytes) : std::string("null"));
  out +=
      ",\"last_error\":" + (s.last_error.empty() ? std::string("null") : jsonString(s.last_error));
  out += ",\"storage\":" + jsonString(s.storage);
  out += ",\"frames\":" + std::to_string(s.frames);
  out += ",\"visits\":" + std::to_string(s.counts.visits);
  out += ",\"strokes\":" + std::to_string(s.counts.strokes);
  out += ",\"gallery_saved\":" + std::to_string(s.counts.gallery_saved);
  out += ",\"saves_failed\":" + std::to_string(s.counts.saves_failed);
  out += ",\"screen\":" + jsonString(s.counts.screen);
  out += "}\n";
  return out;
}

}  // namespace cb
