#include "app/study/likert_statistics.h"

#include <cmath>

#include "app/study/student_t.h"

namespace cb {
namespace {

size_t requireItem(const LikertAnswers& answers, const std::string& id, const std::string& what) {
  const int i = answers.itemIndex(id);
  if (i < 0) throw StudyInputError(what + ": no item '" + id + "' in the answers");
  return size_t(i);
}

}  // namespace

double sampleMean(const std::vector<double>& values) {
  double sum = 0;
  for (double v : values) sum += v;
  return values.empty() ? 0.0 : sum / double(values.size());
}

std::optional<double> sampleStandardDeviation(const std::vector<double>& values) {
  if (values.size() < 2) return std::nullopt;
  const double mean = sampleMean(values);
  double squares = 0;
  for (double v : values) squares += (v - mean) * (v - mean);
  return std::sqrt(squares / double(values.size() - 1));
}

ItemSummary summariseItem(const LikertAnswers& answers, size_t item) {
  ItemSummary s;
  s.item = answers.items.at(item);
  s.counts.assign(size_t(answers.scale_max - answers.scale_min + 1), 0);
  std::vector<double> values;
  for (int v : answers.itemValues(item)) {
    ++s.counts[size_t(v - answers.scale_min)];
    values.push_back(v);
  }
  s.n = values.size();
  if (!values.empty()) s.mean = sampleMean(values);
  s.sd = sampleStandardDeviation(values);
  return s;
}

ConstructSummary summariseConstruct(const LikertAnswers& answers,
                                    const ConstructDefinition& definition) {
  ConstructSummary s;
  s.definition = definition;
  if (definition.items.empty())
    throw StudyInputError("construct '" + definition.name + "': no items");
  std::vector<size_t> columns;
  for (const std::string& id : definition.items)
    columns.push_back(requireItem(answers, id, "construct '" + definition.name + "'"));
  std::vector<double> scores;
  for (const auto& row : answers.answers) {
    double sum = 0;
    size_t n = 0;
    for (size_t c : columns)
      if (row[c]) {
        sum += *row[c];
        ++n;
      }
    if (n > 0) scores.push_back(sum / double(n));
  }
  s.participants = scores.size();
  if (!scores.empty()) s.mean = sampleMean(scores);
  s.sd = sampleStandardDeviation(scores);
  return s;
}

PairedTTest pairedTTest(const LikertAnswers& answers, const std::string& first,
                        const std::string& second) {
  const size_t a = requireItem(answers, first, "paired t-test");
  const size_t b = requireItem(answers, second, "paired t-test");
  PairedTTest test;
  test.first = first;
  test.second = second;
  std::vector<double> first_values, second_values, differences;
  for (const auto& row : answers.answers) {
    if (!row[a] || !row[b]) continue;
    first_values.push_back(*row[a]);
    second_values.push_back(*row[b]);
    differences.push_back(double(*row[b]) - double(*row[a]));
  }
  test.n = differences.size();
  if (test.n < 2)
    throw StudyInputError("paired t-test " + first + " vs " + second + ": " +
                          std::to_string(test.n) + " participants answered both (need 2 or more)");
  test.mean_first = sampleMean(first_values);
  test.mean_second = sampleMean(second_values);
  test.mean_difference = sampleMean(differences);
  test.sd_difference = *sampleStandardDeviation(differences);
  if (test.sd_difference == 0)
    throw StudyInputError("paired t-test " + first + " vs " + second +
                          ": every participant's difference is the same; t is undefined");
  test.degrees_of_freedom = double(test.n - 1);
  test.t = test.mean_difference / (test.sd_difference / std::sqrt(double(test.n)));
  // Upper tails by symmetry, P(T ≥ t) = P(T ≤ −t), which keeps small p-values accurate.
  test.p_one_tailed = studentTCdf(-test.t, test.degrees_of_freedom);
  test.p_two_tailed = 2.0 * studentTCdf(-std::fabs(test.t), test.degrees_of_freedom);
  return test;
}

}  // namespace cb
