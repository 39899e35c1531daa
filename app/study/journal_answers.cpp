#include "app/study/journal_answers.h"

#include <algorithm>
#include <cstdlib>

#include "app/study/study_marker_text.h"

namespace cb {
namespace {

std::optional<int> answerValue(const StudyMarkerFields& m, const SessionTrace& s,
                               const TraceEvent& e, int scale_min, int scale_max) {
  if (m.isNa("value")) return std::nullopt;
  const std::string text = m.get("value");
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || v < scale_min || v > scale_max)
    throw StudyInputError(s.path + ": record " + std::to_string(e.record_index + 1) + ": item " +
                          m.get("item") + ": answer '" + text + "' is not on the scale " +
                          std::to_string(scale_min) + ".." + std::to_string(scale_max));
  return int(v);
}

}  // namespace

LikertAnswers likertAnswersFromSessions(const std::vector<SessionTrace>& sessions,
                                        const std::vector<std::string>& items, int scale_min,
                                        int scale_max) {
  LikertAnswers answers;
  answers.items = items;
  answers.scale_min = scale_min;
  answers.scale_max = scale_max;
  for (const SessionTrace& s : sessions) {
    if (s.participant.empty()) continue;  // not a study session
    if (std::find(answers.participants.begin(), answers.participants.end(), s.participant) !=
        answers.participants.end())
      throw StudyInputError(s.path + ": participant " + s.participant +
                            " is in an earlier session too");
    std::vector<std::optional<int>> row(items.size());
    for (const TraceEvent& e : s.events) {
      if (e.type != JournalRecordType::kMarker || e.text.rfind("study.answer ", 0) != 0) continue;
      const StudyMarkerFields m = parseStudyMarker(e.text);
      if (!m.values.count("item")) continue;  // a demographic field or free text
      const int i = answers.itemIndex(m.get("item"));
      if (i < 0)
        throw StudyInputError(s.path + ": record " + std::to_string(e.record_index + 1) +
                              ": item " + m.get("item") + " is not in the questionnaire");
      row[size_t(i)] = answerValue(m, s, e, scale_min, scale_max);
    }
    answers.participants.push_back(s.participant);
    answers.answers.push_back(std::move(row));
  }
  return answers;
}

}  // namespace cb
