// A tutorial step's checks (tutorial_condition.h) in the participant's words, English and
// Chinese, with where the session stands: `strokes_in_step >= 1` with none painted yet reads
// "Paint one stroke (0 of 1 so far)" / "画一笔（目前 0 / 1）". One table words every variable of
// the checks' vocabulary (tutorialVariables) and every word a word-variable can take; a check the
// table cannot word reads "Do the step's task" rather than its expression. The participant's
// panel shows these words; the expression itself stays the protocol author's (`study check`).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "app/study/study_waiting_words.h"
#include "app/study/tutorial_condition.h"

namespace cb {

// What `condition` asks the participant to do ("Paint one stroke" / "画一笔").
StudyWords tutorialGoalWords(const TutorialCondition& condition);
// The goal and where `state` stands on it: "Paint 4 strokes (2 of 4 so far)", "... (done)".
StudyWords tutorialCheckWords(const TutorialCondition& condition, const TutorialState& state);
// A step's checks one after another ("; " in English, "；" in Chinese).
StudyWords tutorialStepWords(const std::vector<TutorialCondition>& expect,
                             const TutorialState& state);
// Whether the table words `variable` (every variable of tutorialVariables must be).
bool tutorialVariableWorded(std::string_view variable);
// Every Chinese wording of the table (the font atlas holds their glyphs).
std::string tutorialWordsZhText();

}  // namespace cb
