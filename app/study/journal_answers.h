// The questionnaire answers of study sessions read from their journals, the source of truth
// (questionnaire.csv is an export of the same answers): the runner's `study.answer item=ID
// value=V` markers (drivers/core/JOURNAL.md), the last answer to an item counting (an answer
// changed before moving on), a bare NA a skipped item. One row per session that names a
// participant (`study.info`), in the order given; the columns are `items` in order (the
// protocol's questionnaire), an item never answered NA — the rows questionnaire.csv holds.
#pragma once

#include <string>
#include <vector>

#include "app/study/likert_answers.h"
#include "app/study/session_trace.h"

namespace cb {

// Errors (StudyInputError) name the journal and record: an answer that is not an integer on the
// scale, an item not in `items`, a participant in two sessions.
LikertAnswers likertAnswersFromSessions(const std::vector<SessionTrace>& sessions,
                                        const std::vector<std::string>& items, int scale_min = 1,
                                        int scale_max = 5);

}  // namespace cb
