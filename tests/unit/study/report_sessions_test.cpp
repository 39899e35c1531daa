// The study report over recorded sessions of the bundled thesis protocol (the runner's state
// machine on a made-up clock, its records and a pen written as journals, the answers as the
// runner's questionnaire.csv rows): P01 completes with one artefact pen report (a stroke of two
// samples 17.873 mm apart in 1 ms: 17,873 mm/s) and leaves the lag item Q28 unanswered, as does
// P02; P03 is aborted by the operator in the questionnaire after answering three items with 1;
// P04 declines consent. The report must count P01 and P02 only, show Q28 and the lag construct
// as NA (never 0.00), time each session on its own clock, give per-task times from the trials,
// and name the artefact instead of letting it set the speed chart's scale. The real binary
// (`study report`) reports every construct of the protocol the sessions name.
//
// CB_KEEP_REPORT=DIR keeps the journals, answers and report there for looking.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/study/construct_definitions.h"
#include "app/study/journal_answers.h"
#include "app/study/likert_answers.h"
#include "app/study/protocol.h"
#include "app/study/study_report.h"
#include "app/study/study_report_html.h"
#include "app/study/study_run_state.h"
#include "app/study/study_session_record.h"
#include "drivers/core/journal.h"
#include "tests/support/command_run.h"
#include "tests/support/file_text.h"

namespace cb {
namespace {

namespace fs = std::filesystem;
constexpr int64_t kSecond = 1'000'000'000, kMs = 1'000'000;

struct Recording {
  std::vector<StudyRunRecord> markers;
  std::vector<PenSample> samples;
  std::string questionnaire_row;  // the runner's questionnaire.csv row of this participant
  int64_t start_ns = 0, end_ns = 0;
};

// A stroke of `n` tip-down samples 5 ms apart, `step_mm` apart, then a hover sample.
void addStroke(Recording* r, int64_t t, double y_mm, double step_mm, int n = 20) {
  for (int i = 0; i <= n; ++i) {
    PenSample s;
    s.t_ns = t + i * 5 * kMs;
    s.x_mm = 20.0 + step_mm * i;
    s.y_mm = y_mm;
    s.in_proximity = true;
    s.tool = PenTool::kPen;
    const bool tip = i < n;
    s.buttons = tip ? uint32_t(kPenTip) : 0u;
    s.pressure = tip ? 0.5f : 0.0f;
    r->samples.push_back(s);
  }
}

// The pen report glitch the issue met: two tip-down reports 17.873 mm apart 1 ms apart.
void addArtefact(Recording* r, int64_t t) {
  for (int i = 0; i < 3; ++i) {
    PenSample s;
    s.t_ns = t + i * kMs;
    s.x_mm = 30.0 + (i == 1 ? 17.873 : 0.0);
    s.y_mm = 40.0;
    s.in_proximity = true;
    s.tool = PenTool::kPen;
    s.buttons = i < 2 ? uint32_t(kPenTip) : 0u;
    s.pressure = i < 2 ? 0.4f : 0.0f;
    r->samples.push_back(s);
  }
}

void skipOperator(StudyRunState& s, int64_t t) {
  s.requestOperator(OperatorAction::kSkip, t);
  s.chooseReason(0, t);
  if (s.closing()) s.closeStage(t);
}

// Consent, code, introduction; tutorial and free drawing skipped by the operator.
void toTasks(StudyRunState& s, int64_t* t) {
  s.agree(*t += kSecond);
  s.proceed(*t += kSecond);
  s.proceed(*t += kSecond);
  while (s.stage() != StudyStageKind::kTask) skipOperator(s, *t += kSecond);
}

// The four tasks: done after 60 s, time up (10 min), skipped after 30 s, done after 45 s
// painted with a 20 s pause between. Six strokes a task at 60..160 mm/s (1 mm/s more per
// participant number); P01's first task holds the artefact.
void paintTasks(StudyRunState& s, Recording* r, int64_t* t, int number) {
  for (int task = 0; task < 4; ++task) {
    const int64_t begin = *t;
    for (int k = 0; k < 6; ++k)
      addStroke(r, begin + (2 + 3 * k) * kSecond, 10.0 + k, 0.3 + 0.1 * k + 0.005 * number);
    if (task == 0 && number == 1) addArtefact(r, begin + 25 * kSecond);
    switch (task) {
      case 0:
        s.finishTask(*t += 60 * kSecond);
        break;
      case 1:
        s.tick(*t += 600 * kSecond);  // the limit: the runner ticks every frame
        break;
      case 2:
        skipOperator(s, *t += 30 * kSecond);
        break;
      case 3:
        s.requestOperator(OperatorAction::kPause, *t += 25 * kSecond);
        s.chooseReason(0, *t);
        s.requestOperator(OperatorAction::kPause, *t += 20 * kSecond);  // resume
        s.finishTask(*t += 20 * kSecond);
        break;
    }
    ASSERT_TRUE(s.closing() || task == 2) << "task " << task;
    if (s.closing()) s.closeStage(*t += kSecond / 2);
  }
}

// Demographics skipped; the questionnaire answered (1 + (7·i + number) mod 5), `skipped` items
// left NA; free text answered.
void answer(StudyRunState& s, int64_t* t, int number, const std::vector<std::string>& skipped) {
  while (s.stage() == StudyStageKind::kDemographics) s.skipField(*t += kSecond);
  ASSERT_EQ(s.stage(), StudyStageKind::kQuestionnaire);
  const std::vector<QuestionnaireItem>& items = s.protocol().items;
  for (size_t i = 0; i < items.size(); ++i) {
    if (std::find(skipped.begin(), skipped.end(), items[i].id) != skipped.end())
      s.skipItem(*t += kSecond);
    else
      s.answerItem(1 + int(7 * i + size_t(number)) % 5, *t += kSecond);
  }
  while (s.stage() == StudyStageKind::kFreeText) s.answerFreeText("fine", *t += kSecond);
}

enum class Ending { kCompleted, kAbortedInQuestionnaire, kDeclined };

Recording record(const StudyProtocol& p, int number, Ending ending) {
  Recording r;
  int64_t t = 100 * kSecond * number;
  r.start_ns = t;
  StudyRunState s(p, number, t);
  if (ending == Ending::kDeclined) {
    s.decline(t += 4 * kSecond);
  } else {
    toTasks(s, &t);
    paintTasks(s, &r, &t, number);
    if (ending == Ending::kCompleted) {
      answer(s, &t, number, {"Q28"});
    } else {
      while (s.stage() == StudyStageKind::kDemographics) s.skipField(t += kSecond);
      for (int i = 0; i < 3; ++i) s.answerItem(1, t += kSecond);
      s.requestOperator(OperatorAction::kAbort, t += kSecond);
      s.chooseReason(0, t);
    }
  }
  EXPECT_TRUE(s.done()) << number;
  r.end_ns = t;
  r.markers = s.takeRecords();
  const std::string csv = s.questionnaireCsv();
  r.questionnaire_row = csv.substr(csv.find('\n') + 1);
  return r;
}

// The journal: study.info, then the markers and pen samples in time order.
void writeJournal(const StudyProtocol& p, int number, const Recording& r, const std::string& path) {
  JournalWriter journal;
  ASSERT_TRUE(journal.open(path)) << journal.error();
  StudySessionInfo info;
  info.protocol_file = p.source;
  info.protocol_name = p.name;
  info.protocol_version = p.version;
  info.participant_id = "P0" + std::to_string(number);
  info.participant_number = number;
  info.anchor_monotonic_ns = r.start_ns;
  info.anchor_unix_ns = 1'790'000'000LL * kSecond;
  ASSERT_TRUE(
      journal.append(JournalRecordType::kMarker, r.start_ns - kMs, formatStudyInfoMarker(info)));
  size_t m = 0, k = 0;
  while (m < r.markers.size() || k < r.samples.size()) {
    if (k >= r.samples.size() || (m < r.markers.size() && r.markers[m].t_ns <= r.samples[k].t_ns)) {
      ASSERT_TRUE(journal.append(JournalRecordType::kMarker, r.markers[m].t_ns, r.markers[m].text));
      ++m;
    } else {
      ASSERT_TRUE(journal.appendPenSample(r.samples[k++]));
    }
  }
}

using cb::test::readText;

struct Study {
  std::string dir, answers;
  std::vector<std::string> journals;
  std::vector<Recording> recordings;
};

Study recordStudy(const StudyProtocol& p) {
  Study study;
  const char* keep = std::getenv("CB_KEEP_REPORT");
  study.dir =
      keep ? std::string(keep)
           : (fs::temp_directory_path() / ("cb_report_" + std::to_string(::getpid()))).string();
  fs::remove_all(study.dir);
  fs::create_directories(study.dir);
  const Ending endings[] = {Ending::kCompleted, Ending::kCompleted, Ending::kAbortedInQuestionnaire,
                            Ending::kDeclined};
  std::string answers;
  for (int number = 1; number <= 4; ++number) {
    study.recordings.push_back(record(p, number, endings[number - 1]));
    const std::string path = study.dir + "/P0" + std::to_string(number) + ".cbj";
    writeJournal(p, number, study.recordings.back(), path);
    study.journals.push_back(path);
    answers += study.recordings.back().questionnaire_row;
  }
  std::string header = "participant";
  for (const QuestionnaireItem& item : p.items) header += "," + item.id;
  study.answers = study.dir + "/questionnaire.csv";
  std::ofstream(study.answers) << header << "\n" << answers;
  return study;
}

const ItemSummary& itemOf(const StudyReport& r, const std::string& id) {
  for (const ItemSummary& s : r.items)
    if (s.item == id) return s;
  throw std::runtime_error("no item " + id);
}

// Only the two completed sessions count; P03 (aborted) and P04 (declined) are set apart.
void checkCountedAndSetApart(const StudyReport& report) {
  EXPECT_EQ(report.participants, 2u);
  ASSERT_EQ(report.set_apart.size(), 2u);
  EXPECT_EQ(report.set_apart[0].participant, "P03");
  EXPECT_EQ(report.set_apart[0].why.rfind("session aborted", 0), 0u) << report.set_apart[0].why;
  EXPECT_EQ(report.set_apart[1].participant, "P04");
  EXPECT_EQ(report.set_apart[1].why, "session declined");
  // P03 answered Q1..Q3 with 1 before the abort: none of it reaches the statistics.
  const ItemSummary& q1 = itemOf(report, "Q1");
  EXPECT_EQ(q1.n, 2u);
  ASSERT_TRUE(q1.mean.has_value());
  EXPECT_DOUBLE_EQ(*q1.mean, (double(1 + (0 + 1) % 5) + double(1 + (0 + 2) % 5)) / 2);
  ASSERT_EQ(report.constructs.size(), 4u) << "every construct of the protocol";
  EXPECT_EQ(report.constructs[0].participants, 2u);

  // Q28 nobody counted answered: NA with n = 0, and so is the lag construct (Q28 alone).
  const ItemSummary& q28 = itemOf(report, "Q28");
  EXPECT_EQ(q28.n, 0u);
  EXPECT_FALSE(q28.mean.has_value());
  EXPECT_EQ(report.constructs[3].definition.name, "Lag acceptance");
  EXPECT_FALSE(report.constructs[3].mean.has_value());
  EXPECT_EQ(report.constructs[3].participants, 0u);
}

// Session status and duration on the session's clock (study.session → study.end).
void checkSessionsAndTasks(const StudyReport& report, const Study& study) {
  ASSERT_EQ(report.sessions.size(), 4u);
  const char* statuses[] = {"completed", "completed", "aborted", "declined"};
  for (size_t i = 0; i < 4; ++i) {
    const SessionFigures& s = report.sessions[i];
    const Recording& r = study.recordings[i];
    EXPECT_EQ(s.outcome.status, statuses[i]) << s.id;
    EXPECT_NEAR(s.outcome.duration_s, double(r.end_ns - r.start_ns) * 1e-9, 1e-9) << s.id;
    if (!r.samples.empty()) {
      const double pen_span = double(r.samples.back().t_ns - r.samples.front().t_ns) * 1e-9;
      EXPECT_GT(s.outcome.duration_s, pen_span + 60) << s.id << ": not the pen samples' span";
    }
  }

  // Per-task times from the trials: each participant's four tasks, by the stage clock.
  ASSERT_EQ(report.sessions[0].trials.size(), 4u);
  std::vector<double> by_order;
  for (const TrialRow& t : report.sessions[0].trials) by_order.push_back(*t.duration_s);
  EXPECT_NEAR(by_order[0], 60.0, 1e-9);   // done
  EXPECT_NEAR(by_order[1], 600.0, 1e-9);  // time up at the 10-minute limit
  EXPECT_NEAR(by_order[2], 30.0, 1e-9);   // skipped
  EXPECT_NEAR(by_order[3], 45.0, 1e-9);   // done; the 20 s pause not counted
  EXPECT_EQ(report.sessions[0].trials[1].end_reason, "time-up");
  ASSERT_EQ(report.tasks.size(), 4u);
  for (const TaskSummary& t : report.tasks) {
    EXPECT_EQ(t.trials, 3u) << t.task << ": P01, P02 and the aborted P03 painted every task";
    ASSERT_TRUE(t.duration_s.has_value()) << t.task;
  }
}

// The artefact: named, and the median speed stays where the strokes are (60..160 mm/s).
void checkArtefact(const StudyReport& report, const Study& study) {
  const SessionFigures& p01 = report.sessions[0];
  ASSERT_EQ(p01.speed_outliers.size(), 1u);
  EXPECT_NEAR(p01.speed_outliers[0].speed_mm_s, 17873.0, 1e-6);
  // 23 s after the first task's first stroke; times count from study.info, 1 ms before start.
  const Recording& r01 = study.recordings[0];
  EXPECT_NEAR(p01.speed_outliers[0].start_s,
              double(r01.samples[0].t_ns - (r01.start_ns - kMs)) * 1e-9 + 23.0, 1e-9);
  ASSERT_TRUE(p01.speed.has_value());
  EXPECT_GT(p01.speed->median, 60.0);
  EXPECT_LT(p01.speed->median, 170.0);
  EXPECT_TRUE(report.sessions[1].speed_outliers.empty()) << "P02 has no artefact";
}

// The page: NA for Q28 and the lag construct, the set-apart table, the artefact named and
// the speed chart's scale not stretched to it.
void checkPage(const StudyReport& report, const StudyReportOptions& options) {
  const std::string html = studyReportHtml(report, options, 1, 5);
  EXPECT_NE(html.find("<td>Q28</td><td>0</td><td>0</td><td>0</td><td>0</td><td>0</td><td>0</td>"
                      "<td>NA</td>"),
            std::string::npos);
  EXPECT_NE(
      html.find("<td class=\"t\">Lag acceptance</td><td class=\"t\">Q28</td><td>0</td><td>NA</td>"),
      std::string::npos);
  EXPECT_NE(html.find("<h2>Set apart</h2>"), std::string::npos);
  EXPECT_NE(html.find("2 participants counted (2 set apart"), std::string::npos);
  EXPECT_NE(html.find("stroke 6 at "), std::string::npos) << "the artefact named by its stroke";
  EXPECT_NE(html.find(": 17873 mm/s"), std::string::npos);
  const size_t chart = html.find("<title>mean speed per stroke</title>");
  ASSERT_NE(chart, std::string::npos);
  const std::string svg = html.substr(chart, html.find("</svg>", chart) - chart);
  EXPECT_EQ(svg.find(">17873"), std::string::npos) << "the axis does not run to the artefact";
  EXPECT_NE(svg.find("fill=\"#ca0020\""), std::string::npos) << "the artefact's mark";
  EXPECT_NE(html.find("<h2>Tasks</h2>"), std::string::npos);
}

// The real binary: the constructs of the protocol the sessions name, Lag acceptance too.
// `command`: the report command on the CSV and the journals; `page`: the page it wrote.
void checkBinaryReport(const Study& study, const StudyProtocol& p, std::string* command,
                       std::string* page) {
  *command = std::string(CB_CLOUDBRUSH_BIN) + " study report " + study.answers;
  for (const std::string& j : study.journals) *command += " " + j;
  *command += " --out " + study.dir + "/report.html";
  const test::CommandRun run = test::runCommand(*command);
  ASSERT_EQ(run.status, 0) << run.out;
  *page = readText(study.dir + "/report.html");
  EXPECT_NE(page->find(
                "<td class=\"t\">Lag acceptance</td><td class=\"t\">Q28</td><td>0</td><td>NA</td>"),
            std::string::npos);
  EXPECT_NE(page->find("Constructs of the study protocol " + p.source), std::string::npos);
  EXPECT_EQ(page->find("0.00</td><td>–"), std::string::npos) << "no mean of 0.00 anywhere";
}

// The answers from the journals (the source of truth) are the CSV's, and so is the report;
// without the CSV the real binary reports the same page from the journals alone.
void checkJournalsAreTheSource(const Study& study, const StudyProtocol& p,
                               const std::vector<SessionTrace>& traces,
                               const LikertAnswers& answers, const StudyReportOptions& options,
                               const StudyReport& report, const std::string& command,
                               const std::string& page) {
  std::vector<std::string> items;
  for (const QuestionnaireItem& item : p.items) items.push_back(item.id);
  const LikertAnswers from_journals = likertAnswersFromSessions(traces, items);
  EXPECT_EQ(from_journals.items, answers.items);
  EXPECT_EQ(from_journals.participants, answers.participants);
  EXPECT_EQ(from_journals.answers, answers.answers);
  EXPECT_EQ(studyReportHtml(computeStudyReport(from_journals, options, traces), options, 1, 5),
            studyReportHtml(report, options, 1, 5));
  fs::remove(study.answers);  // the export is gone: the journals still report
  std::string journals_only = std::string(CB_CLOUDBRUSH_BIN) + " study report";
  for (const std::string& j : study.journals) journals_only += " " + j;
  journals_only += " --out " + study.dir + "/report_journals.html";
  const test::CommandRun from_journals_run = test::runCommand(journals_only);
  ASSERT_EQ(from_journals_run.status, 0) << from_journals_run.out;
  const std::string journals_page = readText(study.dir + "/report_journals.html");
  const auto without_source = [](std::string html, const std::string& source) {
    for (size_t at = html.find(source); at != std::string::npos; at = html.find(source))
      html.erase(at, source.size());
    return html;
  };
  EXPECT_EQ(without_source(journals_page, "the sessions&#39; journals"),
            without_source(without_source(page, study.answers), "the sessions&#39; journals"))
      << "the same page but for where the answers were read";
  // A CSV that disagrees with the journals is said, and the journals' answers are reported.
  std::ofstream(study.answers) << "participant,Q1\nP01,1\n";
  const test::CommandRun disagreeing = test::runCommand(command);
  EXPECT_EQ(disagreeing.status, 0) << disagreeing.out;
  EXPECT_NE(disagreeing.out.find("P01 Q1 differs from the journals"), std::string::npos)
      << disagreeing.out;
  EXPECT_EQ(without_source(readText(study.dir + "/report.html"), study.answers),
            without_source(page, study.answers));
}

TEST(StudyReportSessions, AbortedDeclinedUnansweredAndAnArtefactOnRecordedSessions) {
  const StudyProtocol p = loadStudyProtocol(defaultStudyProtocolPath());
  const Study study = recordStudy(p);
  std::vector<SessionTrace> traces;
  for (const std::string& path : study.journals) traces.push_back(loadSessionTrace(path));
  const LikertAnswers answers = loadLikertAnswers(study.answers);
  ASSERT_EQ(answers.participants.size(), 4u) << "the runner writes a row for every session";
  StudyReportOptions options;
  for (const ProtocolConstruct& c : p.constructs) options.constructs.push_back({c.name, c.items});
  const StudyReport report = computeStudyReport(answers, options, traces);

  ASSERT_NO_FATAL_FAILURE(checkCountedAndSetApart(report));
  ASSERT_NO_FATAL_FAILURE(checkSessionsAndTasks(report, study));
  ASSERT_NO_FATAL_FAILURE(checkArtefact(report, study));
  ASSERT_NO_FATAL_FAILURE(checkPage(report, options));
  std::string command, page;
  ASSERT_NO_FATAL_FAILURE(checkBinaryReport(study, p, &command, &page));
  ASSERT_NO_FATAL_FAILURE(
      checkJournalsAreTheSource(study, p, traces, answers, options, report, command, page));
  if (!std::getenv("CB_KEEP_REPORT")) fs::remove_all(study.dir);
}

}  // namespace
}  // namespace cb
