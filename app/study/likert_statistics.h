// Summaries of questionnaire answers for the study report.
//
//   Item summary: n answers, the count of each scale point, mean and sample standard deviation
//     s = sqrt(Σ(x − x̄)² / (n − 1)) (the thesis's Table 7.3 and §7.7.2 report these).
//   Construct summary: a construct is a declared group of items; each participant's construct
//     score is the mean of the construct's items they answered (participants with none are left
//     out); the summary is the mean and sample SD of those scores over participants.
//   Paired one-tailed t-test (Student 1908; thesis §7.7.2 compares Q3, the 2D brush, with Q6,
//     the 3D brush): over the n participants who answered both items, d = second − first,
//     t = d̄ / (s_d / √n) with n − 1 degrees of freedom; the one-tailed p is P(T ≥ t), the
//     chance of a difference this large in favour of the second item if there were none
//     (student_t.h); the two-tailed p is 2·P(T ≥ |t|).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "app/study/likert_answers.h"

namespace cb {

struct ItemSummary {
  std::string item;
  size_t n = 0;
  std::vector<size_t> counts;  // counts[k] answers of scale_min + k
  std::optional<double> mean;  // none when nobody answered (NA, never 0)
  std::optional<double> sd;    // none with fewer than 2 answers
};

struct ConstructDefinition {
  std::string name;
  std::vector<std::string> items;
};

struct ConstructSummary {
  ConstructDefinition definition;
  size_t participants = 0;
  std::optional<double> mean;  // none when nobody answered any of its items
  std::optional<double> sd;
  std::vector<std::string> missing_items;  // items not in the answers (the report says so)
};

struct PairedTTest {
  std::string first, second;  // item ids; the alternative is mean(second) > mean(first)
  size_t n = 0;               // participants with both answers
  double mean_first = 0, mean_second = 0;
  double mean_difference = 0, sd_difference = 0;
  double t = 0;
  double degrees_of_freedom = 0;
  double p_one_tailed = 0, p_two_tailed = 0;
};

double sampleMean(const std::vector<double>& values);
// Sample standard deviation (n − 1 in the denominator); none with fewer than 2 values.
std::optional<double> sampleStandardDeviation(const std::vector<double>& values);

ItemSummary summariseItem(const LikertAnswers& answers, size_t item);
// Errors (StudyInputError) name the construct and the unknown item.
ConstructSummary summariseConstruct(const LikertAnswers& answers,
                                    const ConstructDefinition& definition);
// StudyInputError when an item is unknown, fewer than 2 pairs remain, or every difference is
// equal (the t statistic is undefined).
PairedTTest pairedTTest(const LikertAnswers& answers, const std::string& first,
                        const std::string& second);

}  // namespace cb
