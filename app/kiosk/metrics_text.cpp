#include "app/kiosk/metrics_text.h"

#include <cmath>
#include <cstdio>

namespace cb {
namespace {

std::string labelValue(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\\' || c == '"') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out;
}

std::string number(double value) {
  if (std::isnan(value)) return "NaN";
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

void metric(std::string* out, const char* name, const char* type, const char* help,
            const std::string& value, const std::string& labels = "") {
  *out += std::string("# HELP cloudbrush_") + name + " " + help + "\n";
  *out += std::string("# TYPE cloudbrush_") + name + " " + type + "\n";
  *out += std::string("cloudbrush_") + name + (labels.empty() ? "" : "{" + labels + "}") + " " +
          value + "\n";
}

}  // namespace

std::string metricsText(const HealthStatus& s, const std::string& version) {
  std::string out;
  const KioskCounts& c = s.counts;
  metric(&out, "visits_total", "counter", "Visitors who started painting.",
         std::to_string(c.visits));
  metric(&out, "strokes_total", "counter", "Strokes mapped into visitors' clouds.",
         std::to_string(c.strokes));
  metric(&out, "gallery_saved_total", "counter", "Visitors' clouds kept in the gallery.",
         std::to_string(c.gallery_saved));
  metric(&out, "saves_failed_total", "counter",
         "Gallery entries and journals that could not be written.", std::to_string(c.saves_failed));
  metric(&out, "frames_total", "counter", "Frames presented.", std::to_string(s.frames));
  metric(&out, "frames_per_second", "gauge", "Frame rate over the last second.",
         number(s.frames_per_second));
  metric(&out, "last_input_age_seconds", "gauge",
         "Seconds since the last pen, mouse or key input (NaN: none yet).",
         s.last_input_age_s ? number(*s.last_input_age_s) : "NaN");
  metric(&out, "uptime_seconds", "gauge", "Seconds since the kiosk started.", number(s.uptime_s));
  metric(&out, "disk_free_bytes", "gauge",
         "Free bytes on the data dir's file system (NaN: unknown).",
         s.disk_free_bytes ? std::to_string(*s.disk_free_bytes) : "NaN");
  metric(&out, "disk_total_bytes", "gauge", "Size of the data dir's file system (NaN: unknown).",
         s.disk_total_bytes ? std::to_string(*s.disk_total_bytes) : "NaN");
  metric(&out, "storage_ok", "gauge", "1 while saving works, 0 while it does not (disk full).",
         s.storage == "ok" ? "1" : "0");
  metric(&out, "device_info", "gauge", "The pen's state.", "1",
         "state=\"" + labelValue(s.device_state) + "\"");
  metric(&out, "screen_info", "gauge", "The screen showing.", "1",
         "screen=\"" + labelValue(c.screen) + "\"");
  metric(&out, "version_info", "gauge", "The running version.", "1",
         "version=\"" + labelValue(version) + "\"");
  metric(&out, "health_written_timestamp_seconds", "gauge", "When these figures were taken.",
         std::to_string(s.written_unix_s));
  return out;
}

}  // namespace cb
