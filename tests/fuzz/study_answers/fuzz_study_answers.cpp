// Fuzz target: questionnaire answers (participant,Q1..Qn CSV) through the reader, the item,
// construct and paired-test summaries and the HTML report.
#include <cstdint>
#include <sstream>
#include <string>

#include "app/study/construct_definitions.h"
#include "app/study/study_report.h"
#include "app/study/study_report_html.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const cb::LikertAnswers answers = cb::readLikertAnswers(in, "fuzz");
    cb::StudyReportOptions options;
    // Constructs over the first items present, so summaries run on whatever was read.
    if (!answers.items.empty()) options.constructs.push_back({"first", {answers.items.front()}});
    if (answers.items.size() >= 2) {
      options.paired_first = answers.items[0];
      options.paired_second = answers.items[1];
    }
    const cb::StudyReport report = cb::computeStudyReport(answers, options);
    (void)cb::studyReportHtml(report, options, answers.scale_min, answers.scale_max);
  } catch (const cb::StudyInputError&) {
  }
  return 0;
}
