// The questionnaire report: the t distribution against numeric integration, the answers reader's
// errors, construct files, the thesis oracle (thesis_answers.csv, see README.md) and the HTML.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "app/study/construct_definitions.h"
#include "app/study/likert_answers.h"
#include "app/study/likert_statistics.h"
#include "app/study/student_t.h"
#include "app/study/study_report.h"
#include "app/study/study_report_html.h"
#include "drivers/core/pen_sample.h"

namespace cb {
namespace {

const std::string kThesisAnswers = std::string(CB_STUDY_TEST_DIR) + "/thesis_answers.csv";

// P(T ≤ t) by composite Simpson integration of the t density from 0 (CDF(0) = ½), with the
// density's constant from lgamma: independent of the incomplete beta function.
double tCdfBySimpson(double t, double nu) {
  const double c = std::exp(std::lgamma((nu + 1) / 2) - std::lgamma(nu / 2)) / std::sqrt(nu * M_PI);
  const auto f = [&](double x) { return c * std::pow(1 + x * x / nu, -(nu + 1) / 2); };
  const int n = 20000;  // even
  const double h = t / n;
  double sum = f(0) + f(t);
  for (int k = 1; k < n; ++k) sum += (k % 2 ? 4 : 2) * f(k * h);
  return 0.5 + sum * h / 3;
}

TEST(StudentT, CdfMatchesNumericIntegrationOfTheDensity) {
  for (double nu : {1.0, 2.5, 5.0, 16.0, 30.0, 200.0})
    for (double t : {-4.0, -1.3, -0.2, 0.0, 0.6432675, 1.0, 2.1, 5.0})
      EXPECT_NEAR(studentTCdf(t, nu), tCdfBySimpson(t, nu), 1e-9) << "t=" << t << " nu=" << nu;
  // Closed forms: ν = 1 is Cauchy, ν = 2 has F(t) = ½ + t / (2√(2 + t²)).
  EXPECT_NEAR(studentTCdf(1.7, 1.0), 0.5 + std::atan(1.7) / M_PI, 1e-13);
  EXPECT_NEAR(studentTCdf(-0.8, 2.0), 0.5 - 0.8 / (2 * std::sqrt(2 + 0.64)), 1e-13);
  EXPECT_TRUE(std::isnan(studentTCdf(1.0, 0.0)));
}

TEST(StudentT, IncompleteBetaClosedForms) {
  for (double x : {0.01, 0.3, 0.5, 0.77, 0.99}) {
    EXPECT_NEAR(regularizedIncompleteBeta(2.5, 1.0, x), std::pow(x, 2.5), 1e-13);
    EXPECT_NEAR(regularizedIncompleteBeta(1.0, 3.2, x), 1 - std::pow(1 - x, 3.2), 1e-13);
    EXPECT_NEAR(regularizedIncompleteBeta(4.0, 7.0, x) + regularizedIncompleteBeta(7.0, 4.0, 1 - x),
                1.0, 1e-13);
  }
  EXPECT_TRUE(std::isnan(regularizedIncompleteBeta(1, 1, 1.5)));
}

LikertAnswers parse(const std::string& text) {
  std::istringstream in(text);
  return readLikertAnswers(in, "answers.csv");
}

std::string errorOf(const std::string& text) {
  try {
    parse(text);
  } catch (const StudyInputError& e) {
    return e.what();
  }
  return "";
}

TEST(LikertAnswersReader, MissingAnswersAndQuoting) {
  const LikertAnswers a = parse("participant,Q1,Q2\n\"P, one\",5,NA\nP2,,3\n");
  ASSERT_EQ(a.participants.size(), 2u);
  EXPECT_EQ(a.participants[0], "P, one");
  EXPECT_EQ(a.itemValues(0), std::vector<int>({5}));
  EXPECT_EQ(a.itemValues(1), std::vector<int>({3}));
  EXPECT_EQ(a.itemIndex("Q2"), 1);
  EXPECT_EQ(a.itemIndex("Q3"), -1);
}

TEST(LikertAnswersReader, ErrorsNameFileLineColumnAndItem) {
  EXPECT_EQ(errorOf("participant,Q1,Q2\nP1,5,6\n"),
            "answers.csv: line 2, column 3: Q2: '6' is not an answer (expected an integer 1..5 or "
            "NA)");
  EXPECT_EQ(
      errorOf("participant,Q1,Q2\nP1,4.5,1\n").rfind("answers.csv: line 2, column 2: Q1: '4.5'", 0),
      0u);
  EXPECT_NE(errorOf("participant,Q1,Q2\nP1,5\n").find("line 2: expected 3 fields"),
            std::string::npos);
  EXPECT_NE(errorOf("participant,Q1,Q1\n").find("line 1, column 3: item 'Q1' appears twice"),
            std::string::npos);
  EXPECT_NE(errorOf("participant,Q1\nP1,1\nP1,2\n").find("line 3, column 1: participant 'P1'"),
            std::string::npos);
  EXPECT_NE(errorOf("").find("no header"), std::string::npos);
  EXPECT_NE(errorOf("participant,Q1\n\"P1,3\n").find("unclosed quote"), std::string::npos);
}

TEST(LikertStatistics, PairedTestNeedsPairsThatVary) {
  EXPECT_THROW(pairedTTest(parse("participant,A,B\nP1,1,2\n"), "A", "B"), StudyInputError);
  EXPECT_THROW(pairedTTest(parse("participant,A,B\nP1,1,2\nP2,3,4\n"), "A", "B"),
               StudyInputError);  // every difference is 1
  EXPECT_THROW(pairedTTest(parse("participant,A,B\nP1,1,2\nP2,3,5\n"), "A", "C"), StudyInputError);
  // Pairs with a missing answer are left out.
  const PairedTTest t =
      pairedTTest(parse("participant,A,B\nP1,1,2\nP2,3,5\nP3,NA,1\nP4,2,2\n"), "A", "B");
  EXPECT_EQ(t.n, 3u);
  EXPECT_NEAR(t.mean_difference, 1.0, 1e-12);
  EXPECT_NEAR(t.t, 1.0 / (1.0 / std::sqrt(3.0)), 1e-12);
  EXPECT_NEAR(t.p_one_tailed, 1 - tCdfBySimpson(t.t, 2), 1e-9);
}

// The thesis's raw answers (Tables 7.1 and 7.2) and what the thesis and the issue report from
// them: Q19 = 4.82, Q13 = 4.06 ± 0.83, Q15 = 4.00 ± 0.71, Q3 = 3.88, Q6 = 4.06, p = 0.26.
TEST(StudyReportOracle, ThesisAnswersGiveTheThesisFigures) {
  const LikertAnswers answers = loadLikertAnswers(kThesisAnswers);
  ASSERT_EQ(answers.participants.size(), 17u);
  ASSERT_EQ(answers.items.size(), 27u);
  const auto item = [&](const char* id) {
    const int i = answers.itemIndex(id);
    EXPECT_GE(i, 0) << id;
    return summariseItem(answers, size_t(i));
  };
  const auto round2 = [](double v) { return std::round(v * 100) / 100; };
  EXPECT_EQ(round2(*item("Q19").mean), 4.82);
  EXPECT_EQ(round2(*item("Q13").mean), 4.06);
  EXPECT_EQ(round2(*item("Q13").sd), 0.83);
  EXPECT_EQ(round2(*item("Q15").mean), 4.00);
  EXPECT_EQ(round2(*item("Q15").sd), 0.71);
  EXPECT_EQ(round2(*item("Q3").mean), 3.88);
  EXPECT_EQ(round2(*item("Q6").mean), 4.06);
  EXPECT_EQ(item("Q3").n, 17u);
  size_t total = 0;
  for (size_t c : item("Q3").counts) total += c;
  EXPECT_EQ(total, 17u);

  const PairedTTest t = pairedTTest(answers, "Q3", "Q6");
  EXPECT_EQ(t.n, 17u);
  EXPECT_EQ(t.degrees_of_freedom, 16.0);
  EXPECT_EQ(round2(t.p_one_tailed), 0.26);
  // Independently: the same p from integrating the t density.
  EXPECT_NEAR(t.p_one_tailed, 1.0 - tCdfBySimpson(t.t, 16.0), 1e-9);
  EXPECT_NEAR(t.p_two_tailed, 2 * t.p_one_tailed, 1e-12);
}

TEST(StudyReportOracle, HtmlIsSelfContained) {
  const LikertAnswers answers = loadLikertAnswers(kThesisAnswers);
  StudyReportOptions options;
  options.answers_name = "thesis_answers.csv";
  options.constructs = appendixCSections();
  const StudyReport report = computeStudyReport(answers, options);
  ASSERT_EQ(report.constructs.size(), 3u);
  EXPECT_EQ(report.constructs[0].participants, 17u);
  ASSERT_TRUE(report.paired.has_value());
  const std::string html = studyReportHtml(report, options, 1, 5);
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("src="), std::string::npos);
  EXPECT_EQ(html.find("href="), std::string::npos);
  EXPECT_EQ(html.find("@import"), std::string::npos);
  size_t svgs = 0;
  for (size_t at = html.find("<svg"); at != std::string::npos; at = html.find("<svg", at + 1))
    ++svgs;
  EXPECT_EQ(svgs, 2u);                                        // items, constructs
  EXPECT_NE(html.find("<td>0.265</td>"), std::string::npos);  // one-tailed p
  EXPECT_NE(html.find("<td>Q19</td><td>17</td><td>0</td><td>0</td><td>0</td><td>3</td><td>14</td>"
                      "<td>4.82</td><td>0.39</td>"),
            std::string::npos);
}

// A hand-made trace: hover, a 3-sample stroke, hover, a 2-sample stroke, 10 ms apart.
SessionTrace handTrace() {
  SessionTrace trace;
  trace.id = "hand";
  trace.t0_ns = 1'000'000'000;
  const bool tips[] = {false, true, true, true, false, true, true};
  for (int i = 0; i < 7; ++i) {
    PenSample s;
    s.t_ns = trace.t0_ns + 10'000'000 * (i + 1);
    s.x_mm = 3.0 * i;  // 3 mm per sample
    s.buttons = tips[i] ? uint32_t(kPenTip) : 0u;
    s.pressure = tips[i] ? 0.1f * float(i) : 0.0f;
    s.in_proximity = true;
    trace.samples.push_back(s);
    trace.sample_records.push_back(size_t(i));
  }
  return trace;
}

TEST(StudyReportSessions, FiguresAndPlotsPerSession) {
  const SessionFigures f = sessionFigures(handTrace());
  EXPECT_EQ(f.samples, 7u);
  EXPECT_EQ(f.strokes, 2u);
  // Not a study session: its own first to last record (the first sample is 10 ms after t0).
  EXPECT_EQ(f.outcome.status, "not-a-study");
  EXPECT_NEAR(f.outcome.duration_s, 0.070, 1e-12);
  EXPECT_NEAR(f.tip_down_s, 0.020 + 0.010, 1e-12);
  ASSERT_EQ(f.pressure.size(), 5u);
  EXPECT_NEAR(f.pressure_t.front(), 0.020, 1e-12);
  EXPECT_FLOAT_EQ(float(f.pressure.back()), 0.6f);
  ASSERT_EQ(f.stroke_speed.size(), 2u);
  EXPECT_NEAR(f.stroke_speed[0], 6.0 / 0.020, 1e-9);  // 6 mm in 20 ms
  EXPECT_NEAR(f.stroke_speed[1], 3.0 / 0.010, 1e-9);

  const LikertAnswers answers = loadLikertAnswers(kThesisAnswers);
  StudyReportOptions options;
  const StudyReport report = computeStudyReport(answers, options, {handTrace(), handTrace()});
  const std::string html = studyReportHtml(report, options, 1, 5);
  size_t svgs = 0;
  for (size_t at = html.find("<svg"); at != std::string::npos; at = html.find("<svg", at + 1))
    ++svgs;
  EXPECT_EQ(svgs, 1u + 2u * 2u);  // items; pressure and speed per session (no constructs given)
  EXPECT_NE(
      html.find(
          "<tr><td class=\"t\">hand</td><td class=\"t\">NA</td><td class=\"t\">not-a-study</td>"
          "<td>0.1</td><td>0.0</td>"
          "<td>7</td><td>2</td>"),
      std::string::npos);
}

TEST(StudyReportSessions, TapsHaveNoSpeedAndDoNotPullTheMedianDown) {
  SessionTrace trace = handTrace();
  // The last stroke lifts; then three taps in place (two tip-down samples each, 10 ms apart),
  // as on the runner's pages.
  for (int i = 0; i < 1 + 3 * 3; ++i) {
    PenSample s = trace.samples.back();
    s.t_ns += 10'000'000;
    s.buttons = i % 3 == 0 ? 0u : uint32_t(kPenTip);
    trace.samples.push_back(s);
    trace.sample_records.push_back(trace.sample_records.size());
  }
  const SessionFigures f = sessionFigures(trace);
  EXPECT_EQ(f.strokes, 5u);
  ASSERT_EQ(f.stroke_speed.size(), 2u) << "the two strokes that moved";
  ASSERT_TRUE(f.speed.has_value());
  EXPECT_NEAR(f.speed->median, (300.0 + 300.0) / 2, 1e-9);
}

TEST(StudyReportOracle, WithoutSessionsARowOfOnlyNAIsSetApartAndAnUnansweredItemIsNA) {
  const LikertAnswers answers = parse("participant,Q1,Q2\nP1,5,NA\nP2,NA,NA\nP3,3,NA\n");
  StudyReportOptions options;
  options.constructs = {{"second", {"Q2"}}, {"missing", {"Q9"}}};
  const StudyReport report = computeStudyReport(answers, options);
  EXPECT_EQ(report.participants, 2u);
  ASSERT_EQ(report.set_apart.size(), 1u);
  EXPECT_EQ(report.set_apart[0].participant, "P2");
  EXPECT_EQ(report.set_apart[0].why, "answered no item");
  EXPECT_FALSE(report.items[1].mean.has_value());
  ASSERT_EQ(report.constructs.size(), 2u);
  EXPECT_FALSE(report.constructs[0].mean.has_value());
  EXPECT_EQ(report.constructs[1].missing_items, std::vector<std::string>({"Q9"}));
  const std::string html = studyReportHtml(report, options, 1, 5);
  EXPECT_NE(html.find("<td>Q2</td><td>0</td><td>0</td><td>0</td><td>0</td><td>0</td><td>0</td>"
                      "<td>NA</td>"),
            std::string::npos);
  EXPECT_NE(html.find("missing: the answers have no Q9."), std::string::npos);
  EXPECT_EQ(html.find(">0.00<"), std::string::npos) << "no mean of 0.00";
}

TEST(ConstructFile, DeclaredConstructsAndTheirErrors) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("cb_constructs_" + std::to_string(::getpid()) + ".toml"))
                               .string();
  const auto write = [&](const std::string& text) { std::ofstream(path) << text; };
  write("[[construct]]\nname = \"Brushes\"\nitems = [\"Q3\", \"Q6\"]\n");
  const std::vector<ConstructDefinition> c = loadConstructDefinitions(path);
  ASSERT_EQ(c.size(), 1u);
  const ConstructSummary s = summariseConstruct(loadLikertAnswers(kThesisAnswers), c[0]);
  // Per participant the mean of Q3 and Q6; overall mean = (Q3 mean + Q6 mean) / 2 here.
  EXPECT_NEAR(*s.mean, (66.0 / 17 + 69.0 / 17) / 2, 1e-12);
  const auto error = [&](const std::string& text) {
    write(text);
    try {
      loadConstructDefinitions(path);
    } catch (const StudyInputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(
      error("[[construct]]\nname = \"A\"\nitems = []\n").find(path + ": construct 1 (A): items"),
      std::string::npos);
  EXPECT_NE(error("[[construct]]\nitems = [\"Q1\"]\n").find("construct 1: name"),
            std::string::npos);
  EXPECT_NE(error("[[construct]]\nname = \"A\"\nitems = [\"Q1\"]\nweight = 2\n")
                .find("unknown field 'weight'"),
            std::string::npos);
  EXPECT_NE(error("x = 1\n").find("no [[construct]]"), std::string::npos);
  EXPECT_THROW(summariseConstruct(loadLikertAnswers(kThesisAnswers), {"X", {"Q99"}}),
               StudyInputError);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace cb
