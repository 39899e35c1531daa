// The questionnaire answers of a BIDS dataset's sessions as BIDS phenotype files (BIDS 1.9,
// "Modality agnostic files: phenotypic and assessment data"): one TSV per questionnaire of the
// study protocol, a row per session (participant_id, session_id, then a column per question),
// and a JSON sidecar that describes the questionnaire (MeasurementToolMetadata) and every
// question: its statement in English (Description) and Chinese (Description_zh), the scale's
// levels in both languages, the protocol's constructs and section.
//
//   phenotype/questionnaire.tsv/.json  the Likert items (study.answer item=ID value=N|NA)
//   phenotype/feedback.tsv/.json       the free-text questions (study.answer free_text=ID ...)
//
// An answer given twice (the participant went back) counts as its last value; n/a: skipped or
// never reached.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "app/study/protocol.h"
#include "app/study/session_trace.h"

namespace cb {

struct BidsPhenotypeRow {
  std::string participant_id, session_id;               // "sub-P01", "ses-1"
  std::map<std::string, std::string> items, free_text;  // id → answer ("" when NA)
};

// The answers a session's journal records.
BidsPhenotypeRow phenotypeAnswers(const SessionTrace& trace);

// Files (relative path → content) for `rows`; nothing for a questionnaire the protocol lacks.
std::map<std::string, std::string> bidsPhenotypeFiles(const StudyProtocol& protocol,
                                                      const std::vector<BidsPhenotypeRow>& rows);

}  // namespace cb
