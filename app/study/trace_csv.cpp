#include "app/study/trace_csv.h"

#include "app/study/csv_text.h"
#include "app/study/export_columns.h"
#include "app/study/stroke_table.h"

namespace cb {
namespace {

const char* toolName(PenTool tool) {
  switch (tool) {
    case PenTool::kPen:
      return "pen";
    case PenTool::kEraser:
      return "eraser";
    case PenTool::kNone:
      break;
  }
  return "none";
}

// A 0-based index, NA when negative.
std::string indexOrMissing(int64_t index) {
  return index < 0 ? std::string(kCsvMissing) : std::to_string(index);
}

}  // namespace

std::string eventKindName(JournalRecordType type) {
  switch (type) {
    case JournalRecordType::kMode:
      return "mode";
    case JournalRecordType::kUi:
      return "ui";
    case JournalRecordType::kMarker:
      return "marker";
    case JournalRecordType::kCalibration:
      return "calibration";
    case JournalRecordType::kSession:
      return "session";
    case JournalRecordType::kDevice:
      return "device";
    case JournalRecordType::kPenSample:
      return "sample";
    case JournalRecordType::kSettings:
      return "settings";
    case JournalRecordType::kStrokeMapped:
      return "stroke_mapped";
    case JournalRecordType::kSync:
      return "sync";
    case JournalRecordType::kFrame:
      return "frame";
  }
  return "type-" + std::to_string(static_cast<uint32_t>(type));
}

void writeSamplesCsvHeader(std::ostream& out) {
  out << csvHeaderLine(sampleColumns());
}

void writeSamplesCsvRows(std::ostream& out, const SessionTrace& trace) {
  {
    const std::string session = csvFieldOrMissing(trace.participant) + ',' + csvField(trace.id);
    // The gesture (strokes.csv row) and the painter's stroke of each sample.
    const SampleGestures of = sampleGestures(trace, measureStrokes(trace));
    for (size_t i = 0; i < trace.samples.size(); ++i) {
      const PenSample& s = trace.samples[i];
      out << session << ',' << i << ',' << s.t_ns << ','
          << decimalSecondsFromNs(elapsedNs(s.t_ns, trace.t0_ns)) << ',' << s.x_raw << ','
          << s.y_raw << ',' << csvDouble(s.x_mm) << ',' << csvDouble(s.y_mm) << ','
          << s.pressure_raw << ',' << csvFloat(s.pressure) << ',' << s.tilt_x_raw << ','
          << s.tilt_y_raw << ',' << csvFloat(s.tilt_x_deg) << ',' << csvFloat(s.tilt_y_deg) << ','
          << s.distance_raw << ',' << csvFloat(s.distance) << ',' << s.buttons << ','
          << (s.tipDown() ? 1 : 0) << ',' << (s.in_proximity ? 1 : 0) << ',' << toolName(s.tool)
          << ',' << s.tool_id << ',' << s.tool_serial << ',';
      out << indexOrMissing(of.gesture[i]) << ',' << indexOrMissing(of.stroke[i]) << ','
          << csvFieldOrMissing(sampleTask(trace, i)) << '\n';
    }
  }
}

void writeStrokesCsvHeader(std::ostream& out) {
  out << csvHeaderLine(strokeColumns());
}

void writeStrokesCsvRows(std::ostream& out, const SessionTrace& trace) {
  {
    const std::string session = csvFieldOrMissing(trace.participant) + ',' + csvField(trace.id);
    for (const StrokeMeasures& m : measureStrokes(trace)) {
      out << session << ',' << m.index << ',' << m.kind << ','
          << indexOrMissing(m.stroke ? int64_t(*m.stroke) : -1) << ',' << csvDouble(m.start_s)
          << ',' << csvDouble(m.duration_s) << ',' << m.sample_count << ','
          << csvDouble(m.path_length_mm) << ',' << csvDouble(m.mean_pressure) << ','
          << csvDouble(m.max_pressure) << ',' << csvDouble(m.mean_tilt_deg) << ','
          << csvOptional(m.speed_mm_s) << ',' << csvFieldOrMissing(m.brush) << ','
          << csvFieldOrMissing(m.mode) << ',' << csvOptional(m.mapping_ms) << ','
          << csvFieldOrMissing(sampleTask(trace, m.first_sample)) << '\n';
    }
  }
}

void writeEventsCsvHeader(std::ostream& out) {
  out << csvHeaderLine(eventColumns());
}

void writeEventsCsvRows(std::ostream& out, const SessionTrace& trace) {
  {
    const std::string session = csvFieldOrMissing(trace.participant) + ',' + csvField(trace.id);
    for (const TraceEvent& e : trace.events) {
      std::string key, value;
      if (e.type == JournalRecordType::kUi) {
        const size_t eq = e.text.find('=');
        key = e.text.substr(0, eq);
        if (eq != std::string::npos) value = e.text.substr(eq + 1);
      } else if (e.type == JournalRecordType::kMode) {
        key = "mode";
        value = e.text;
      } else {
        value = e.text;
      }
      out << session << ',' << decimalSecondsFromNs(elapsedNs(e.t_ns, trace.t0_ns)) << ','
          << e.record_index << ',' << eventKindName(e.type) << ',' << csvFieldOrMissing(key) << ','
          << csvFieldOrMissing(value) << ',' << csvFieldOrMissing(e.task) << '\n';
    }
  }
}

void writeSamplesCsv(std::ostream& out, const std::vector<SessionTrace>& sessions) {
  writeSamplesCsvHeader(out);
  for (const SessionTrace& trace : sessions) writeSamplesCsvRows(out, trace);
}

void writeStrokesCsv(std::ostream& out, const std::vector<SessionTrace>& sessions) {
  writeStrokesCsvHeader(out);
  for (const SessionTrace& trace : sessions) writeStrokesCsvRows(out, trace);
}

void writeEventsCsv(std::ostream& out, const std::vector<SessionTrace>& sessions) {
  writeEventsCsvHeader(out);
  for (const SessionTrace& trace : sessions) writeEventsCsvRows(out, trace);
}

}  // namespace cb
