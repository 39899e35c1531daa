#include "app/study/stroke_table.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "calibration/tilt.h"
#include "drivers/core/journal_records.h"

namespace cb {
namespace {

// The value of a "key=value" UI record text when its key is `key`.
std::optional<std::string> uiValue(const std::string& text, const std::string& key) {
  if (text.size() > key.size() && text.compare(0, key.size(), key) == 0 && text[key.size()] == '=')
    return text.substr(key.size() + 1);
  return std::nullopt;
}

}  // namespace

std::vector<StrokeMeasures> measureStrokes(const SessionTrace& trace) {
  std::vector<StrokeMeasures> strokes;
  std::string brush, mode;
  size_t next_event = 0;
  // Applies every event recorded before journal record `record`.
  const auto advanceEvents = [&](size_t record) {
    for (; next_event < trace.events.size() && trace.events[next_event].record_index < record;
         ++next_event) {
      const TraceEvent& e = trace.events[next_event];
      if (e.type == JournalRecordType::kMode) mode = e.text;
      if (e.type == JournalRecordType::kUi)
        if (auto value = uiValue(e.text, "brush")) brush = *value;
    }
  };
  const std::vector<PenSample>& s = trace.samples;
  size_t i = 0;
  while (i < s.size()) {
    if (!s[i].tipDown()) {
      ++i;
      continue;
    }
    size_t end = i;
    while (end < s.size() && s[end].tipDown()) ++end;
    advanceEvents(trace.sample_records.empty() ? 0 : trace.sample_records[i]);
    StrokeMeasures m;
    m.index = static_cast<uint32_t>(strokes.size());
    m.first_sample = i;
    m.sample_count = end - i;
    m.start_s = double(elapsedNs(s[i].t_ns, trace.t0_ns)) * 1e-9;
    m.duration_s = double(elapsedNs(s[end - 1].t_ns, s[i].t_ns)) * 1e-9;
    double pressure_sum = 0, tilt_sum = 0;
    for (size_t k = i; k < end; ++k) {
      pressure_sum += s[k].pressure;
      m.max_pressure = std::max(m.max_pressure, double(s[k].pressure));
      tilt_sum += 90.0 - tiltToAzimuthAltitude(s[k].tilt_x_deg, s[k].tilt_y_deg).altitude_deg;
      if (k > i)
        m.path_length_mm += std::hypot(s[k].x_mm - s[k - 1].x_mm, s[k].y_mm - s[k - 1].y_mm);
    }
    m.mean_pressure = pressure_sum / double(m.sample_count);
    m.mean_tilt_deg = tilt_sum / double(m.sample_count);
    if (m.duration_s > 0) m.speed_mm_s = m.path_length_mm / m.duration_s;
    m.brush = brush;
    m.mode = mode;
    strokes.push_back(m);
    i = end;
  }
  // Mapping times: the first StrokeMapped record between a stroke's first sample and the next
  // stroke's (the painter maps at its own, calibrated lift, a few samples after the raw one).
  if (!trace.sample_records.empty())
    for (size_t k = 0; k < strokes.size(); ++k) {
      const size_t from = trace.sample_records[strokes[k].first_sample];
      const size_t to =
          k + 1 < strokes.size() ? trace.sample_records[strokes[k + 1].first_sample] : SIZE_MAX;
      for (const TraceEvent& e : trace.events) {
        if (e.type != JournalRecordType::kStrokeMapped || e.record_index <= from ||
            e.record_index >= to)
          continue;
        if (const std::optional<StrokeMappedRecord> r = parseStrokeMapped(e.text))
          strokes[k].mapping_ms = r->mapping_ms;
        break;
      }
    }
  return strokes;
}

}  // namespace cb
