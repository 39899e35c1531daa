// codebook.csv: what every exported variable means, for a reader without our code (an analyst,
// a data archive's curator). One row per variable:
//   file        the export that holds it: questionnaire.csv, demographics.csv, trials.csv,
//               strokes.csv, samples.csv, events.csv
//   variable    its column name (questionnaire.csv: the item id, Q1..Qn)
//   type        integer | number | text | category
//   unit        the unit (s, ns, mm, deg, device units, ...), or NA where none applies
//   meaning     what it is and how it was made
//   text_en / text_zh  a questionnaire item's statement or a demographic question, in English
//               and in Chinese (NA where the protocol gives no Chinese text)
//   scale_min / scale_max / anchors  a Likert item's scale: 1..n and "1=strongly disagree; ..."
//               (a demographic number's allowed range; a choice's answers in `anchors`)
//   construct   the constructs the protocol puts the item in ("; " between several), or NA
//   section     the questionnaire's section (thesis Appendix C), or NA
// The columns of the pen-trace and trial tables are the ones their writers emit
// (trace_csv.h, trial_table.h: read from the header each writes, not a copy of it), each
// described by one table here; a column the table does not know gets an empty meaning, which
// the codebook test refuses.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "app/study/protocol.h"

namespace cb {

struct CodebookRow {
  std::string file, variable, type, unit, meaning;
  std::string text_en, text_zh;
  std::string scale_min, scale_max, anchors;
  std::string construct, section;
};

// The names a CSV header writer emits (its first line, split at commas).
std::vector<std::string> csvHeaderColumns(void (*write_header)(std::ostream&));

// Every variable of the exports of a study run with `protocol`.
std::vector<CodebookRow> studyCodebook(const StudyProtocol& protocol);

// codebook.csv (columns as above; missing values NA).
void writeCodebookCsv(std::ostream& out, const std::vector<CodebookRow>& rows);

}  // namespace cb
