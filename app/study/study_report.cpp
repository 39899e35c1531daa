#include "app/study/study_report.h"

#include <algorithm>
#include <map>
#include <set>

#include "app/study/stroke_table.h"

namespace cb {
namespace {

// Tip-down pressure against time, at most ~2000 points evenly kept.
void keepPressure(const SessionTrace& trace, size_t tip_down, SessionFigures* f) {
  const size_t stride = tip_down > 2000 ? (tip_down + 1999) / 2000 : 1;
  size_t k = 0;
  for (const PenSample& s : trace.samples) {
    if (!s.tipDown()) continue;
    if (k++ % stride != 0) continue;
    f->pressure_t.push_back(double(elapsedNs(s.t_ns, trace.t0_ns)) * 1e-9);
    f->pressure.push_back(s.pressure);
  }
}

// The strokes' figures: count, tip-down time, speeds and the speed outliers named.
void measureSessionStrokes(const SessionTrace& trace, SessionFigures* f) {
  const std::vector<StrokeMeasures> gestures = measureStrokes(trace);
  size_t tip_down = 0;
  std::vector<const StrokeMeasures*> with_speed;
  for (const StrokeMeasures& m : gestures) {
    // The painter's strokes only: erase drags, menu and form taps and view drags are the
    // session's other gestures (strokes.csv's kind).
    if (m.kind != "stroke") continue;
    ++f->strokes;
    f->tip_down_s += m.duration_s;
    tip_down += m.sample_count;
    // A tap on the runner's pages or a dab in place has no speed to speak of: only strokes
    // that moved enter the speed figures (else a session of button taps has a median of 0).
    if (!m.speed_mm_s || m.path_length_mm <= 0) continue;
    f->stroke_start_s.push_back(m.start_s);
    f->stroke_speed.push_back(*m.speed_mm_s);
    with_speed.push_back(&m);
  }
  f->speed = robustSummary(f->stroke_speed);
  // With fewer than 4 strokes the quartiles say too little to call a stroke an outlier.
  if (f->speed && f->speed->n >= 4)
    for (size_t i : f->speed->outliers) {
      const StrokeMeasures& m = *with_speed[i];
      f->speed_outliers.push_back({m.stroke.value_or(m.index), m.start_s, *m.speed_mm_s,
                                   sampleTask(trace, m.first_sample), i});
    }
  keepPressure(trace, tip_down, f);
}

// The answers of the participants who count; the others are added to *set_apart.
LikertAnswers countedAnswers(const LikertAnswers& answers,
                             const std::vector<SessionFigures>& sessions,
                             std::vector<SetApartParticipant>* set_apart) {
  std::set<std::string> completed;
  std::map<std::string, const SessionFigures*> ended_otherwise;
  for (const SessionFigures& s : sessions) {
    if (s.participant.empty()) continue;
    if (s.outcome.counts())
      completed.insert(s.participant);
    else if (!ended_otherwise.count(s.participant))
      ended_otherwise[s.participant] = &s;
  }
  for (const auto& [participant, s] : ended_otherwise)
    if (!completed.count(participant))
      set_apart->push_back({participant, s->id,
                            "session " + s->outcome.status +
                                (s->outcome.reason.empty() ? "" : " (" + s->outcome.reason + ")")});
  LikertAnswers kept = answers;
  kept.participants.clear();
  kept.answers.clear();
  for (size_t p = 0; p < answers.participants.size(); ++p) {
    const std::string& id = answers.participants[p];
    if (ended_otherwise.count(id) && !completed.count(id)) continue;
    bool any = false;
    for (const auto& a : answers.answers[p]) any = any || a.has_value();
    if (!any) {
      set_apart->push_back({id, "", "answered no item"});
      continue;
    }
    kept.participants.push_back(id);
    kept.answers.push_back(answers.answers[p]);
  }
  return kept;
}

// A construct over the items the answers have; the others are listed as missing.
ConstructSummary summariseConstructOfPresentItems(const LikertAnswers& answers,
                                                  const ConstructDefinition& definition) {
  ConstructDefinition present{definition.name, {}};
  std::vector<std::string> missing;
  for (const std::string& id : definition.items)
    (answers.itemIndex(id) >= 0 ? present.items : missing).push_back(id);
  ConstructSummary s;
  if (!present.items.empty()) s = summariseConstruct(answers, present);
  s.definition = definition;
  s.missing_items = missing;
  return s;
}

}  // namespace

SessionFigures sessionFigures(const SessionTrace& trace) {
  SessionFigures f;
  f.timing = frameTimingStats(trace.frames);
  f.id = trace.id;
  f.participant = trace.participant;
  f.outcome = sessionOutcome(trace);
  f.samples = trace.samples.size();
  f.trials = trialsOfSession(trace);
  measureSessionStrokes(trace, &f);
  return f;
}

std::vector<TaskSummary> summariseTasks(const std::vector<SessionFigures>& sessions) {
  std::vector<TaskSummary> tasks;
  std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> values;
  for (const SessionFigures& s : sessions)
    for (const TrialRow& t : s.trials) {
      auto it = std::find_if(tasks.begin(), tasks.end(),
                             [&](const TaskSummary& k) { return k.task == t.task; });
      if (it == tasks.end()) {
        it = tasks.emplace(tasks.end());
        it->task = t.task;
      }
      ++it->trials;
      if (t.duration_s) values[t.task].first.push_back(*t.duration_s);
      values[t.task].second.push_back(double(t.strokes));
      const std::string reason = t.end_reason.empty() ? "unfinished" : t.end_reason;
      auto r = std::find_if(it->end_reasons.begin(), it->end_reasons.end(),
                            [&](const auto& e) { return e.first == reason; });
      if (r == it->end_reasons.end())
        it->end_reasons.emplace_back(reason, 1);
      else
        ++r->second;
    }
  for (TaskSummary& t : tasks) {
    t.duration_s = robustSummary(values[t.task].first);
    t.strokes = robustSummary(values[t.task].second);
  }
  return tasks;
}

StudyReport computeStudyReport(const LikertAnswers& all_answers, const StudyReportOptions& options,
                               const std::vector<SessionTrace>& sessions) {
  StudyReport report;
  for (const SessionTrace& trace : sessions) report.sessions.push_back(sessionFigures(trace));
  report.tasks = summariseTasks(report.sessions);
  const LikertAnswers answers = countedAnswers(all_answers, report.sessions, &report.set_apart);
  report.participants = answers.participants.size();
  for (size_t i = 0; i < answers.items.size(); ++i)
    report.items.push_back(summariseItem(answers, i));
  for (const ConstructDefinition& c : options.constructs)
    report.constructs.push_back(summariseConstructOfPresentItems(answers, c));
  try {
    report.paired = pairedTTest(answers, options.paired_first, options.paired_second);
  } catch (const StudyInputError& e) {
    report.paired_problem = e.what();
  }
  return report;
}

}  // namespace cb
