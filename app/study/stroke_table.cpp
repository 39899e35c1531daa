#include "app/study/stroke_table.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <map>

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

// The painter's state in force at a journal position: mode, brush, whether the UI holds the pen.
class PainterContext {
 public:
  explicit PainterContext(const SessionTrace& trace) : trace_(trace) {}
  // Applies every event recorded before journal record `record` (positions only grow).
  void advanceTo(size_t record) {
    for (; next_ < trace_.events.size() && trace_.events[next_].record_index < record; ++next_) {
      const TraceEvent& e = trace_.events[next_];
      if (e.type == JournalRecordType::kMode) mode = e.text;
      if (e.type != JournalRecordType::kUi) continue;
      if (auto value = uiValue(e.text, "brush")) brush = *value;
      if (auto value = uiValue(e.text, "pen_capture")) captured = *value == "on";
    }
  }
  // What a tip-down run that made no painter stroke was.
  std::string unmappedKind() const {
    if (captured) return "menu_tap";
    if (mode == "erase") return "erase";
    if (mode.empty() || mode == "paint") return "unmapped";
    return mode;
  }
  std::string mode, brush;
  bool captured = false;

 private:
  const SessionTrace& trace_;
  size_t next_ = 0;
};

// The painter's strokes as the journal has them: where each began (the sample whose feed wrote
// the stroke_begin Sync record, i.e. the last sample before it) and its mapping time.
struct PainterStrokes {
  std::map<size_t, uint32_t> begin_at_sample;  // sample → painter stroke index
  std::map<uint32_t, double> mapping_ms;       // painter stroke index → StrokeMapped time
  bool has_sync = false;                       // journals before Sync records have none
};

PainterStrokes painterStrokes(const SessionTrace& trace) {
  PainterStrokes p;
  for (const TraceEvent& e : trace.events) {
    if (e.type == JournalRecordType::kStrokeMapped) {
      if (const std::optional<StrokeMappedRecord> r = parseStrokeMapped(e.text))
        p.mapping_ms.emplace(r->stroke, r->mapping_ms);
      continue;
    }
    if (e.type != JournalRecordType::kSync) continue;
    const std::optional<SyncMarker> marker = parseSyncMarker(e.text);
    if (!marker || marker->kind != "stroke_begin") continue;
    const auto after =
        std::upper_bound(trace.sample_records.begin(), trace.sample_records.end(), e.record_index);
    if (after == trace.sample_records.begin()) continue;  // no sample began it
    p.has_sync = true;
    const size_t sample = size_t(after - trace.sample_records.begin()) - 1;
    p.begin_at_sample[sample] = uint32_t(std::strtoul(marker->label.c_str(), nullptr, 10));
  }
  return p;
}

// The raw measures of samples [from, to).
StrokeMeasures measure(const SessionTrace& trace, size_t from, size_t to) {
  const std::vector<PenSample>& s = trace.samples;
  StrokeMeasures m;
  m.first_sample = from;
  m.sample_count = to - from;
  m.start_s = double(elapsedNs(s[from].t_ns, trace.t0_ns)) * 1e-9;
  m.duration_s = double(elapsedNs(s[to - 1].t_ns, s[from].t_ns)) * 1e-9;
  double pressure_sum = 0, tilt_sum = 0;
  for (size_t k = from; k < to; ++k) {
    pressure_sum += s[k].pressure;
    m.max_pressure = std::max(m.max_pressure, double(s[k].pressure));
    tilt_sum += 90.0 - tiltToAzimuthAltitude(s[k].tilt_x_deg, s[k].tilt_y_deg).altitude_deg;
    if (k > from)
      m.path_length_mm += std::hypot(s[k].x_mm - s[k - 1].x_mm, s[k].y_mm - s[k - 1].y_mm);
  }
  m.mean_pressure = pressure_sum / double(m.sample_count);
  m.mean_tilt_deg = tilt_sum / double(m.sample_count);
  if (m.duration_s > 0) m.speed_mm_s = m.path_length_mm / m.duration_s;
  return m;
}

}  // namespace

std::vector<StrokeMeasures> measureStrokes(const SessionTrace& trace) {
  std::vector<StrokeMeasures> rows;
  PainterContext context(trace);
  const PainterStrokes painter = painterStrokes(trace);
  uint32_t legacy_index = 0;
  const auto addRow = [&](size_t from, size_t to, std::optional<uint32_t> stroke) {
    context.advanceTo(trace.sample_records.empty() ? 0 : trace.sample_records[from]);
    StrokeMeasures m = measure(trace, from, to);
    m.index = uint32_t(rows.size());
    m.brush = context.brush;
    m.mode = context.mode;
    if (!painter.has_sync && !stroke && !context.captured &&
        (context.mode.empty() || context.mode == "paint"))
      stroke = legacy_index++;
    m.stroke = stroke;
    m.kind = stroke ? "stroke" : context.unmappedKind();
    if (stroke)
      if (auto at = painter.mapping_ms.find(*stroke); at != painter.mapping_ms.end())
        m.mapping_ms = at->second;
    rows.push_back(std::move(m));
  };
  const std::vector<PenSample>& s = trace.samples;
  size_t i = 0;
  while (i < s.size()) {
    if (!s[i].tipDown()) {
      // A stroke the painter began without the raw tip bit: its row runs to the next tip-down.
      if (auto b = painter.begin_at_sample.find(i); b != painter.begin_at_sample.end()) {
        size_t end = i + 1;
        while (end < s.size() && !s[end].tipDown() && !painter.begin_at_sample.count(end)) ++end;
        addRow(i, end, b->second);
        i = end;
      } else {
        ++i;
      }
      continue;
    }
    size_t end = i;
    while (end < s.size() && s[end].tipDown()) ++end;
    // The run, cut where the painter began a stroke inside it; the samples before the first
    // begin belong to that stroke.
    auto b = painter.begin_at_sample.lower_bound(i);
    if (b == painter.begin_at_sample.end() || b->first >= end) {
      addRow(i, end, std::nullopt);
    } else {
      size_t from = i;
      while (b != painter.begin_at_sample.end() && b->first < end) {
        const auto next = std::next(b);
        const size_t to =
            next != painter.begin_at_sample.end() && next->first < end ? next->first : end;
        addRow(from, to, b->second);
        from = to;
        b = next;
      }
    }
    i = end;
  }
  return rows;
}

SampleGestures sampleGestures(const SessionTrace& trace, const std::vector<StrokeMeasures>& rows) {
  SampleGestures g;
  g.gesture.assign(trace.samples.size(), -1);
  g.stroke.assign(trace.samples.size(), -1);
  for (const StrokeMeasures& m : rows)
    for (size_t k = m.first_sample; k < m.first_sample + m.sample_count; ++k) {
      g.gesture[k] = m.index;
      if (m.stroke) g.stroke[k] = *m.stroke;
    }
  return g;
}

}  // namespace cb
