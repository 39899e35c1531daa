// What a study page waits for, in words, English and Chinese (the foot line of every page the
// study runner shows; StudyRunState::waitingWords picks the line and its values). One table of
// wordings: each line's English and Chinese side by side, their `%s` filled with the same values
// in order (a participant code, a step number, a countdown: ASCII, so the Chinese glyphs the page
// needs are the table's own, studyWaitingZhText). A Chinese wording may leave a value out (the
// operator's reasons are English words for the operator).
#pragma once

#include <string>
#include <vector>

namespace cb {

// A text in English and Chinese.
struct StudyWords {
  std::string en, zh;
};

enum class StudyWaitLine {
  kChoosePause,    // the operator chooses why to pause
  kChooseSkip,     // ... why to skip
  kChooseAbort,    // ... why to abort
  kPaused,         // %s: the pause's reason (English only)
  kClosing,        // %s: why the painting stage ends (English only)
  kConsent,        //
  kParticipant,    // %s: the participant code
  kIntroduction,   //
  kTutorial,       // %s, %s: the step, the number of steps
  kPaintTimed,     // free drawing; %s: the countdown
  kPaint,          // free drawing without a limit
  kTaskTimed,      // %s: the countdown
  kTask,           // a task without a limit
  kDemographics,   //
  kQuestionnaire,  //
  kFreeText,       //
  kDeclined,       // the end: consent declined
  kAborted,        // the end: the operator aborted
  kDone,           // the end: all done
  kCount
};

// `line` with `values` in place of its `%s`, in order (missing values: "").
StudyWords studyWaitingWords(StudyWaitLine line, const std::vector<std::string>& values = {});
// Every Chinese wording of the table, one after another (the font atlas holds their glyphs).
std::string studyWaitingZhText();

}  // namespace cb
