#include "app/study/study_report.h"

#include "app/study/stroke_table.h"

namespace cb {

SessionFigures sessionFigures(const SessionTrace& trace) {
  SessionFigures f;
  f.timing = frameTimingStats(trace.frames);
  f.id = trace.id;
  f.samples = trace.samples.size();
  if (!trace.samples.empty())
    f.duration_s = double(elapsedNs(trace.samples.back().t_ns, trace.samples.front().t_ns)) * 1e-9;
  const std::vector<StrokeMeasures> strokes = measureStrokes(trace);
  f.strokes = strokes.size();
  size_t tip_down = 0;
  for (const StrokeMeasures& m : strokes) {
    f.tip_down_s += m.duration_s;
    tip_down += m.sample_count;
    if (m.speed_mm_s) {
      f.stroke_start_s.push_back(m.start_s);
      f.stroke_speed.push_back(*m.speed_mm_s);
    }
  }
  const size_t stride = tip_down > 2000 ? (tip_down + 1999) / 2000 : 1;
  size_t k = 0;
  for (const PenSample& s : trace.samples) {
    if (!s.tipDown()) continue;
    if (k++ % stride != 0) continue;
    f.pressure_t.push_back(double(elapsedNs(s.t_ns, trace.t0_ns)) * 1e-9);
    f.pressure.push_back(s.pressure);
  }
  return f;
}

StudyReport computeStudyReport(const LikertAnswers& answers, const StudyReportOptions& options,
                               const std::vector<SessionTrace>& sessions) {
  StudyReport report;
  report.participants = answers.participants.size();
  for (size_t i = 0; i < answers.items.size(); ++i)
    report.items.push_back(summariseItem(answers, i));
  for (const ConstructDefinition& c : options.constructs)
    report.constructs.push_back(summariseConstruct(answers, c));
  try {
    report.paired = pairedTTest(answers, options.paired_first, options.paired_second);
  } catch (const StudyInputError& e) {
    report.paired_problem = e.what();
  }
  for (const SessionTrace& trace : sessions) report.sessions.push_back(sessionFigures(trace));
  return report;
}

}  // namespace cb
