// The study pages' foot-line wordings (app/study/study_waiting_words.h): every line has its
// English and its Chinese, the Chinese uses no value the English lacks, values fill both in order
// and leave no `%s`, the atlas text holds every Chinese wording, and StudyRunState's waitingFor is
// the English of its waitingWords on each stage of the bundled protocol.
#include <gtest/gtest.h>

#include "app/core/config_paths.h"
#include "app/study/protocol.h"
#include "app/study/study_run_state.h"
#include "app/study/study_waiting_words.h"

namespace cb {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

int placeholders(const std::string& text) {
  int n = 0;
  for (size_t at = text.find("%s"); at != std::string::npos; at = text.find("%s", at + 2)) ++n;
  return n;
}

bool hasCjk(const std::string& text) {  // U+4E00..U+9FFF lead bytes
  for (unsigned char c : text)
    if (c >= 0xe4 && c <= 0xe9) return true;
  return false;
}

bool ascii(const std::string& text) {
  for (unsigned char c : text)
    if (c >= 0x80) return false;
  return true;
}

TEST(StudyWaitingWords, EveryLineHasEnglishAndChineseFilledAlike) {
  const std::string atlas = studyWaitingZhText();
  for (int i = 0; i < int(StudyWaitLine::kCount); ++i) {
    const StudyWaitLine line = StudyWaitLine(i);
    const StudyWords raw = studyWaitingWords(line, {"%s", "%s"});  // the templates as they are
    SCOPED_TRACE("line " + std::to_string(i) + ": " + raw.en);
    EXPECT_FALSE(raw.en.empty());
    EXPECT_TRUE(ascii(raw.en)) << "the English is plain ASCII";
    EXPECT_TRUE(hasCjk(raw.zh)) << raw.zh;
    EXPECT_LE(placeholders(raw.zh), placeholders(raw.en)) << raw.zh;
    EXPECT_NE(atlas.find(raw.zh), std::string::npos) << "the atlas text lacks " << raw.zh;
    const StudyWords filled = studyWaitingWords(line, {"P07", "12"});
    EXPECT_EQ(placeholders(filled.en) + placeholders(filled.zh), 0) << filled.en << filled.zh;
  }
  const StudyWords step = studyWaitingWords(StudyWaitLine::kTutorial, {"2", "5"});
  EXPECT_EQ(step.en.rfind("Step 2 of 5:", 0), 0u) << step.en;
  EXPECT_EQ(step.zh.rfind("第 2 步，共 5 步", 0), 0u) << step.zh;
  const StudyWords code = studyWaitingWords(StudyWaitLine::kParticipant, {"P07"});
  EXPECT_NE(code.zh.find("P07"), std::string::npos) << code.zh;
}

TEST(StudyWaitingWords, WaitingForIsTheEnglishOfWaitingWordsOnEveryStage) {
  const StudyProtocol protocol = loadStudyProtocol(defaultStudyProtocolPath());
  int64_t t = 100 * kSecond;
  StudyRunState s(protocol, 1, t);
  int stages = 0;
  const auto expectBoth = [&] {
    const StudyWords w = s.waitingWords(t);
    EXPECT_EQ(w.en, s.waitingFor(t)) << studyStageName(s.stage());
    EXPECT_TRUE(hasCjk(w.zh)) << studyStageName(s.stage()) << ": " << w.zh;
    ++stages;
  };
  for (int guard = 0; !s.done() && guard < 1000; ++guard) {
    t += kSecond;
    expectBoth();
    switch (s.stage()) {
      case StudyStageKind::kConsent:
        s.agree(t);
        break;
      case StudyStageKind::kParticipant:
      case StudyStageKind::kIntroduction:
        s.proceed(t);
        break;
      case StudyStageKind::kTutorial:
        if (s.closing())
          s.closeStage(t);
        else
          s.completeTutorialStep(t);
        break;
      case StudyStageKind::kFreeDrawing:
      case StudyStageKind::kTask:
        if (s.closing()) {
          s.closeStage(t);
        } else {
          s.requestOperator(OperatorAction::kPause, t);  // choosing, then paused
          expectBoth();
          s.chooseReason(0, t);
          expectBoth();
          s.requestOperator(OperatorAction::kPause, t);
          if (s.stage() == StudyStageKind::kTask) {
            s.finishTask(t);
          } else {
            s.requestOperator(OperatorAction::kSkip, t);  // free drawing has no "I'm done"
            s.chooseReason(0, t);
          }
          EXPECT_TRUE(s.closing()) << studyStageName(s.stage());
          expectBoth();
        }
        break;
      case StudyStageKind::kDemographics:
        s.skipField(t);
        break;
      case StudyStageKind::kQuestionnaire:
        s.skipItem(t);
        break;
      case StudyStageKind::kFreeText:
        s.answerFreeText("", t);
        break;
      case StudyStageKind::kDone:
        break;
    }
  }
  ASSERT_TRUE(s.done()) << "stuck at " << studyStageName(s.stage());
  expectBoth();
  EXPECT_GT(stages, 10);
}

}  // namespace
}  // namespace cb
