// The study report's figures, computed from questionnaire answers and (optionally) session
// traces: Likert distributions per item, construct summaries, the paired comparison of two items
// (by default Q3 vs Q6, the thesis's 2D and 3D brush ratings, §7.7.2) and per-session pen
// figures. study_report_html.h turns it into the offline HTML page.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "app/study/frame_timing_stats.h"
#include "app/study/likert_statistics.h"
#include "app/study/session_trace.h"

namespace cb {

struct StudyReportOptions {
  std::string title = "cloudbrush user study";
  std::string answers_name;  // shown in the page (the CSV's path)
  std::vector<ConstructDefinition> constructs;
  std::string constructs_source;  // where the constructs were declared, shown in the page
  std::string paired_first = "Q3", paired_second = "Q6";
};

struct SessionFigures {
  std::string id;
  double duration_s = 0;  // first to last pen sample
  size_t samples = 0, strokes = 0;
  double tip_down_s = 0;                     // summed stroke durations
  std::vector<double> pressure_t, pressure;  // tip-down samples (at most ~2000, evenly kept)
  std::vector<double> stroke_start_s, stroke_speed;  // per stroke with a speed (mm/s)
  FrameTimingStats timing;  // from the journal's Frame records (none in older journals)
};

struct StudyReport {
  size_t participants = 0;
  std::vector<ItemSummary> items;
  std::vector<ConstructSummary> constructs;
  std::optional<PairedTTest> paired;
  std::string paired_problem;  // why the paired test could not be computed, else empty
  std::vector<SessionFigures> sessions;
};

// Constructs that name unknown items raise StudyInputError; a paired test that cannot be
// computed is reported in paired_problem (the rest of the report stands).
StudyReport computeStudyReport(const LikertAnswers& answers, const StudyReportOptions& options,
                               const std::vector<SessionTrace>& sessions = {});

SessionFigures sessionFigures(const SessionTrace& trace);

}  // namespace cb
