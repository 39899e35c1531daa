// trials.csv: one row per task a participant painted, read from the runner's markers in the
// session's journal (drivers/core/JOURNAL.md section 7):
//   participant, session, task, order (its position in the participant's task order),
//   onset_s (seconds after the journal's first record), onset_monotonic_ns (the marker's t_ns),
//   onset_wall_clock_unix_ns (from study.info's clock anchor: wall + (t − monotonic); NA when the
//   journal has no anchor), duration_s (the stage clock at study.stage-closing: pauses and a
//   resumed session's downtime not counted; NA when the task never closed), end_reason
//   (time-up, done, skipped, aborted, or NA when the journal ends inside the task), strokes
//   (StrokeMapped records in paint mode: the painter's mapped strokes), erases (StrokeMapped in
//   erase mode, and vacuum cuts), undos (Ui `undo`).
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "app/study/session_trace.h"

namespace cb {

struct TrialRow {
  std::string task;
  int order = 0;
  int64_t onset_ns = 0;
  std::optional<int64_t> onset_unix_ns;
  std::optional<double> duration_s;
  std::string end_reason;  // empty: the journal ended inside the task
  int strokes = 0, erases = 0, undos = 0;
};

std::vector<TrialRow> trialsOfSession(const SessionTrace& trace);

// "time up" → time-up, "skipped: ..." → skipped, "aborted: ..." → aborted, "done" → done.
std::string trialEndReason(const std::string& why);

void writeTrialsCsvHeader(std::ostream& out);
void writeTrialsCsvRows(std::ostream& out, const SessionTrace& trace);

}  // namespace cb
