#include "app/study/trial_table.h"

#include <cstdlib>

#include "app/study/csv_text.h"
#include "app/study/export_columns.h"
#include "app/study/study_marker_text.h"

namespace cb {
namespace {

struct ClockAnchor {
  int64_t monotonic_ns = 0, unix_ns = 0;
  bool known = false;
};

// What a non-marker event adds to the open trial's counts.
void countEvent(const TraceEvent& e, bool erasing, TrialRow* trial) {
  if (e.type == JournalRecordType::kStrokeMapped) ++(erasing ? trial->erases : trial->strokes);
  if (e.type == JournalRecordType::kUi && e.text == "undo") ++trial->undos;
  if (e.type == JournalRecordType::kUi && e.text.rfind("vacuum_cut=", 0) == 0) ++trial->erases;
}

}  // namespace

std::string trialEndReason(const std::string& why) {
  if (why == "time up") return "time-up";
  if (why.rfind("skipped", 0) == 0) return "skipped";
  if (why.rfind("aborted", 0) == 0) return "aborted";
  if (why.rfind("done", 0) == 0) return "done";
  return why.empty() ? "" : "other";
}

std::vector<TrialRow> trialsOfSession(const SessionTrace& trace) {
  std::vector<TrialRow> rows;
  ClockAnchor anchor;
  bool open = false, erasing = false;
  for (const TraceEvent& e : trace.events) {
    if (e.type == JournalRecordType::kMode) erasing = e.text == "erase";
    if (e.type != JournalRecordType::kMarker || e.text.rfind("study.", 0) != 0) {
      if (open) countEvent(e, erasing, &rows.back());
      continue;
    }
    const StudyMarkerFields m = parseStudyMarker(e.text);
    if (m.event == "study.info" && m.has("monotonic_ns") && m.has("wall_clock_unix_ns")) {
      anchor.monotonic_ns = std::strtoll(m.get("monotonic_ns").c_str(), nullptr, 10);
      anchor.unix_ns = std::strtoll(m.get("wall_clock_unix_ns").c_str(), nullptr, 10);
      anchor.known = true;
    } else if (m.event == "study.stage-begin" && m.get("stage") == "task") {
      TrialRow row;
      row.task = m.get("task");
      row.order = std::atoi(m.get("position").c_str());
      row.onset_ns = e.t_ns;
      if (anchor.known) row.onset_unix_ns = anchor.unix_ns + (e.t_ns - anchor.monotonic_ns);
      rows.push_back(row);
      open = true;
    } else if (open && m.event == "study.stage-closing") {
      rows.back().duration_s = std::strtod(m.get("seconds").c_str(), nullptr);
      rows.back().end_reason = trialEndReason(m.get("why"));
    } else if (open && (m.event == "study.stage-end" || m.event == "study.end")) {
      open = false;
    }
  }
  return rows;
}

void writeTrialsCsvHeader(std::ostream& out) {
  out << csvHeaderLine(trialColumns());
}

void writeTrialsCsvRows(std::ostream& out, const SessionTrace& trace) {
  const std::string session = csvFieldOrMissing(trace.participant) + ',' + csvField(trace.id);
  for (const TrialRow& t : trialsOfSession(trace)) {
    out << session << ',' << csvField(t.task) << ',' << t.order << ','
        << decimalSecondsFromNs(elapsedNs(t.onset_ns, trace.t0_ns)) << ',' << t.onset_ns << ',';
    if (t.onset_unix_ns)
      out << *t.onset_unix_ns;
    else
      out << kCsvMissing;
    out << ',' << csvOptional(t.duration_s) << ',' << csvFieldOrMissing(t.end_reason) << ','
        << t.strokes << ',' << t.erases << ',' << t.undos << '\n';
  }
}

}  // namespace cb
