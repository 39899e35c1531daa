// The study report's figures, computed from questionnaire answers and (optionally) session
// traces: Likert distributions per item, construct summaries, the paired comparison of two items
// (by default Q3 vs Q6, the thesis's 2D and 3D brush ratings, §7.7.2), per-task times from the
// sessions' trials, and per-session figures. study_report_html.h turns it into the offline HTML
// page.
//
// Who counts: a participant whose sessions (among those given) all ended aborted, declined or
// unfinished, and a participant who answered no item at all, is set apart (listed with why) and
// left out of every questionnaire statistic; only their session figures are shown.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "app/study/frame_timing_stats.h"
#include "app/study/likert_statistics.h"
#include "app/study/robust_statistics.h"
#include "app/study/session_outcome.h"
#include "app/study/session_trace.h"
#include "app/study/trial_table.h"

namespace cb {

struct StudyReportOptions {
  std::string title = "cloudbrush user study";
  std::string answers_name;  // shown in the page (the CSV's path)
  // Constructs to summarise. Items a construct names that the answers lack are listed in the
  // page (ConstructSummary::missing_items), never dropped in silence.
  std::vector<ConstructDefinition> constructs;
  std::string constructs_source;  // where the constructs were declared, shown in the page
  std::string paired_first = "Q3", paired_second = "Q6";
};

// A stroke whose mean speed lies beyond the session's outer fences (robust_statistics.h).
struct StrokeOutlier {
  uint32_t stroke = 0;  // strokes.csv's stroke number
  double start_s = 0, speed_mm_s = 0;
  std::string task;  // the task it was painted in, "" outside tasks
  size_t point = 0;  // its index in SessionFigures::stroke_speed
};

struct SessionFigures {
  std::string id, participant;
  SessionOutcome outcome;  // status and duration on the session's clock
  size_t samples = 0, strokes = 0;
  double tip_down_s = 0;                     // summed stroke durations
  std::vector<double> pressure_t, pressure;  // tip-down samples (at most ~2000, evenly kept)
  // Per stroke that moved (path length > 0: taps and dabs left out), its mean speed (mm/s).
  std::vector<double> stroke_start_s, stroke_speed;
  std::optional<RobustSummary> speed;  // of stroke_speed
  std::vector<StrokeOutlier> speed_outliers;
  std::vector<TrialRow> trials;  // trials.csv's rows
  FrameTimingStats timing;       // from the journal's Frame records (none in older journals)
};

// One task over every session's trial of it.
struct TaskSummary {
  std::string task;
  size_t trials = 0;
  std::optional<RobustSummary> duration_s;  // of the trials that closed
  std::optional<RobustSummary> strokes;
  std::vector<std::pair<std::string, size_t>> end_reasons;  // reason → trials, first seen first
};

struct SetApartParticipant {
  std::string participant, session, why;  // session: "" when set apart for their answers
};

struct StudyReport {
  size_t participants = 0;  // the answers' rows the statistics use
  std::vector<SetApartParticipant> set_apart;
  std::vector<ItemSummary> items;
  std::vector<ConstructSummary> constructs;
  std::optional<PairedTTest> paired;
  std::string paired_problem;  // why the paired test could not be computed, else empty
  std::vector<SessionFigures> sessions;
  std::vector<TaskSummary> tasks;  // in the order tasks first appear
};

// A paired test that cannot be computed is reported in paired_problem (the rest of the report
// stands).
StudyReport computeStudyReport(const LikertAnswers& answers, const StudyReportOptions& options,
                               const std::vector<SessionTrace>& sessions = {});

SessionFigures sessionFigures(const SessionTrace& trace);
std::vector<TaskSummary> summariseTasks(const std::vector<SessionFigures>& sessions);

}  // namespace cb
