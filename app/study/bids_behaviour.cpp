#include "app/study/bids_behaviour.h"

#include <algorithm>
#include <optional>
#include <vector>

#include "app/study/bids_text.h"
#include "app/study/export_columns.h"
#include "app/study/study_marker_text.h"
#include "app/study/trial_table.h"

namespace cb {
namespace {

const std::vector<BidsColumn>& behColumns() {
  static const std::vector<BidsColumn> columns = bidsColumnsOf(trialColumns());
  return columns;
}

const std::vector<BidsColumn>& eventTsvColumns() {
  static const std::vector<BidsColumn> columns = bidsColumnsOf(bidsEventColumns());
  return columns;
}

struct EventRow {
  int64_t onset_ns = 0;
  std::optional<int64_t> end_ns;
  std::string type, task, reason;
  std::optional<TrialRow> trial;
};

// The stages and pauses of a session from its study markers, in journal order.
std::vector<EventRow> sessionEvents(const SessionTrace& trace) {
  const std::vector<TrialRow> trials = trialsOfSession(trace);
  size_t next_trial = 0;
  std::vector<EventRow> rows;
  constexpr size_t kNone = ~size_t(0);
  size_t stage = kNone, pause = kNone;  // the open stage's and pause's rows
  const auto close = [&](size_t& open, int64_t t) {
    if (open != kNone) rows[open].end_ns = t;
    open = kNone;
  };
  for (const TraceEvent& e : trace.events) {
    if (e.type != JournalRecordType::kMarker || e.text.rfind("study.", 0) != 0) continue;
    const StudyMarkerFields m = parseStudyMarker(e.text);
    if (m.event == "study.stage-begin") {
      close(stage, e.t_ns);
      EventRow row{e.t_ns, std::nullopt, m.get("stage"), m.get("task"), "", std::nullopt};
      if (row.type == "task" && next_trial < trials.size()) row.trial = trials[next_trial++];
      rows.push_back(row);
      stage = rows.size() - 1;
    } else if (m.event == "study.stage-end" || m.event == "study.end") {
      close(stage, e.t_ns);
      close(pause, e.t_ns);
    } else if (m.event == "study.operator" && m.get("action") == "pause") {
      rows.push_back({e.t_ns, std::nullopt, "pause", "", m.get("reason"), std::nullopt});
      pause = rows.size() - 1;
    } else if (m.event == "study.operator" && m.get("action") == "resume") {
      close(pause, e.t_ns);
    }
  }
  std::stable_sort(rows.begin(), rows.end(),
                   [](const EventRow& a, const EventRow& b) { return a.onset_ns < b.onset_ns; });
  return rows;
}

std::string eventLine(const SessionTrace& trace, const EventRow& r) {
  const std::string na = kBidsMissing;
  std::string line = bidsSeconds(elapsedNs(r.onset_ns, trace.t0_ns)) + '\t' +
                     (r.end_ns ? bidsSeconds(elapsedNs(*r.end_ns, r.onset_ns)) : na) + '\t' +
                     bidsTsvText(r.type) + '\t' + bidsTsvText(r.task) + '\t';
  if (r.trial)
    line += std::to_string(r.trial->order) + '\t' + bidsTsvNumber(r.trial->duration_s) + '\t' +
            bidsTsvText(r.trial->end_reason) + '\t' + std::to_string(r.trial->strokes) + '\t' +
            std::to_string(r.trial->erases) + '\t' + std::to_string(r.trial->undos);
  else
    line += na + '\t' + na + '\t' + na + '\t' + na + '\t' + na + '\t' + na;
  return line + '\t' + (r.type == "pause" ? bidsTsvText(r.reason) : na) + '\n';
}

}  // namespace

std::string bidsBehTsv(const SessionTrace& trace) {
  std::string out = bidsTsvHeader(behColumns());
  const std::string session = bidsTsvText(trace.participant) + '\t' + bidsTsvText(trace.id);
  for (const TrialRow& t : trialsOfSession(trace))
    out += session + '\t' + bidsTsvText(t.task) + '\t' + std::to_string(t.order) + '\t' +
           bidsSeconds(elapsedNs(t.onset_ns, trace.t0_ns)) + '\t' + std::to_string(t.onset_ns) +
           '\t' + (t.onset_unix_ns ? std::to_string(*t.onset_unix_ns) : kBidsMissing) + '\t' +
           bidsTsvNumber(t.duration_s) + '\t' + bidsTsvText(t.end_reason) + '\t' +
           std::to_string(t.strokes) + '\t' + std::to_string(t.erases) + '\t' +
           std::to_string(t.undos) + '\n';
  return out;
}

std::string bidsBehJson() {
  return bidsColumnsJson(behColumns());
}

std::string bidsEventsTsv(const SessionTrace& trace) {
  std::string out = bidsTsvHeader(eventTsvColumns());
  for (const EventRow& r : sessionEvents(trace)) out += eventLine(trace, r);
  return out;
}

std::string bidsEventsJson() {
  return bidsColumnsJson(eventTsvColumns());
}

}  // namespace cb
