// Questionnaire answers, one row per participant (questionnaire.csv):
//
//   participant,Q1,Q2,...,Qn
//   P01,5,5,4,...
//   P02,4,NA,...
//
// The first column names the participant (any non-empty text, unique); every other column is an
// item whose header is its id. Answers are integers on the item scale (1..5 by default: strongly
// disagree .. strongly agree); NA or an empty field is a missing answer. RFC 4180 quoting is
// accepted. Anything else — a duplicate item or participant, a row with too few or too many
// fields, an answer off the scale — raises StudyInputError naming the file, line and column.
#pragma once

#include <istream>
#include <optional>
#include <string>
#include <vector>

#include "app/study/session_trace.h"  // StudyInputError

namespace cb {

struct LikertAnswers {
  std::vector<std::string> items;         // column headers after the participant column
  std::vector<std::string> participants;  // row order
  // answers[p][i]: participant p's answer to item i, none when missing.
  std::vector<std::vector<std::optional<int>>> answers;
  int scale_min = 1, scale_max = 5;

  // Index of item `id`, or -1.
  int itemIndex(const std::string& id) const;
  // The answers given to item i (missing ones left out), in participant order.
  std::vector<int> itemValues(size_t i) const;
};

LikertAnswers readLikertAnswers(std::istream& in, const std::string& name, int scale_min = 1,
                                int scale_max = 5);
LikertAnswers loadLikertAnswers(const std::string& path, int scale_min = 1, int scale_max = 5);

// Splits one CSV record (RFC 4180 quoting, no embedded line breaks); false on an unclosed quote.
bool splitCsvLine(const std::string& line, std::vector<std::string>* fields);

}  // namespace cb
