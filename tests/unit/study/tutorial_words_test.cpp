// The tutorial checks in the participant's words (app/study/tutorial_words.h): every variable of
// the checks' vocabulary (tutorialVariables) is worded, in English and Chinese, for every
// comparison its kind allows and every word it can take (a variable added without a wording fails
// here); the bundled protocol's checks all read as plain words, with no operator or variable name
// left in them; the status says how far the participant is; a check the table cannot word reads
// a neutral task; and the atlas text holds every Chinese wording.
#include <gtest/gtest.h>

#include "app/core/config_paths.h"
#include "app/study/protocol.h"
#include "app/study/tutorial_words.h"

namespace cb {
namespace {

bool hasCjk(const std::string& text) {  // U+4E00..U+9FFF lead bytes
  for (unsigned char c : text)
    if (c >= 0xe4 && c <= 0xe9) return true;
  return false;
}

// What an expression would leave in words: a comparison, a variable's underscore, a template's
// placeholder.
std::string expressionLeft(const std::string& text) {
  for (const char* mark : {"==", "!=", ">=", "<=", ">", "<", "_", "%"})
    if (text.find(mark) != std::string::npos) return mark;
  return "";
}

const char* const kFallbackEn = "Do the step's task";

// Every check the kind of `v` allows: each comparison against each word, true and false, or a
// few numbers.
std::vector<std::string> everyCheck(const TutorialVariable& v) {
  const std::string name(v.name);
  std::vector<std::string> checks;
  switch (v.kind) {
    case ConditionKind::kWord:
      for (std::string_view w : v.words)
        for (const char* op : {" == ", " != "}) checks.push_back(name + op + std::string(w));
      break;
    case ConditionKind::kBoolean:
      for (const char* value : {"true", "false"})
        for (const char* op : {" == ", " != "}) checks.push_back(name + op + value);
      break;
    case ConditionKind::kInteger:
      for (const char* op : {" == ", " != ", " < ", " <= ", " > ", " >= "})
        for (const char* n : {"1", "4", "96"}) checks.push_back(name + op + n);
      break;
  }
  return checks;
}

TEST(TutorialWords, EveryVariableOfTheVocabularyIsWordedForEveryCheckItAllows) {
  ASSERT_FALSE(tutorialVariables().empty());
  for (const TutorialVariable& v : tutorialVariables()) {
    SCOPED_TRACE(std::string(v.name));
    EXPECT_TRUE(tutorialVariableWorded(v.name)) << "no wording for " << v.name;
    for (const std::string& text : everyCheck(v)) {
      const StudyWords goal = tutorialGoalWords(parseTutorialCondition(text));
      SCOPED_TRACE(text + " reads \"" + goal.en + "\" / \"" + goal.zh + "\"");
      EXPECT_NE(goal.en, kFallbackEn);
      EXPECT_EQ(expressionLeft(goal.en), "");
      EXPECT_EQ(expressionLeft(goal.zh), "");
      EXPECT_TRUE(hasCjk(goal.zh));
    }
  }
}

TEST(TutorialWords, TheBundledProtocolsChecksReadAsPlainWords) {
  const StudyProtocol protocol = loadStudyProtocol(defaultStudyProtocolPath());
  ASSERT_FALSE(protocol.tutorial.empty());
  const TutorialState nothing;  // the session holds no value yet: "not yet"
  TutorialState fresh;          // at a step's start: Camera mode, nothing counted
  fresh.words = {{"mode", "camera"}, {"camera_view", "free"}};
  for (const char* counter : {"strokes_in_step", "brush_changes_in_step", "erasures_in_step",
                              "undos_in_step", "saves_in_step"})
    fresh.numbers[counter] = 0;
  fresh.numbers["camera_elevation_deg"] = 30;
  fresh.numbers["canvas_altitude"] = 128;
  fresh.numbers["cloud_empty"] = 0;
  fresh.numbers["circles_shown"] = 1;
  const TutorialState* const states[] = {&nothing, &fresh};
  for (size_t i = 0; i < protocol.tutorial.size(); ++i) {
    for (const TutorialState* state : states) {
      const StudyWords words = tutorialStepWords(protocol.tutorial[i].expect, *state);
      SCOPED_TRACE("step " + std::to_string(i + 1) + ": \"" + words.en + "\" / \"" + words.zh +
                   "\"");
      EXPECT_EQ(expressionLeft(words.en), "");
      EXPECT_EQ(expressionLeft(words.zh), "");
      EXPECT_EQ(words.en.find(kFallbackEn), std::string::npos);
      EXPECT_TRUE(hasCjk(words.zh));
    }
  }
}

TEST(TutorialWords, TheStatusSaysHowFarTheParticipantIs) {
  const TutorialCondition one = parseTutorialCondition("strokes_in_step >= 1");
  TutorialState s;
  EXPECT_EQ(tutorialCheckWords(one, s).en, "Paint one stroke (not yet)");
  s.numbers["strokes_in_step"] = 0;
  const StudyWords none = tutorialCheckWords(one, s);
  EXPECT_EQ(none.en, "Paint one stroke (0 of 1 so far)");
  EXPECT_EQ(none.zh, "画一笔（目前 0 / 1）");
  s.numbers["strokes_in_step"] = 1;
  EXPECT_EQ(tutorialCheckWords(one, s).en, "Paint one stroke (done)");
  EXPECT_EQ(tutorialCheckWords(one, s).zh, "画一笔（已完成）");

  s.numbers["strokes_in_step"] = 2;
  EXPECT_EQ(tutorialCheckWords(parseTutorialCondition("strokes_in_step >= 4"), s).en,
            "Paint 4 strokes (2 of 4 so far)");
  s.numbers["canvas_altitude"] = 80;
  EXPECT_EQ(tutorialCheckWords(parseTutorialCondition("canvas_altitude == 96"), s).en,
            "Set the canvas altitude to 96 (now 80)");
  s.numbers["camera_elevation_deg"] = 30;
  const StudyWords tilt =
      tutorialCheckWords(parseTutorialCondition("camera_elevation_deg >= 60"), s);
  EXPECT_EQ(tilt.en, "Tilt the view down to at least 60 degrees (now 30 degrees)");
  EXPECT_EQ(tilt.zh, "把视角向下倾斜到至少 60 度（现在是 30 度）");
  s.words["mode"] = "camera";
  const StudyWords mode = tutorialCheckWords(parseTutorialCondition("mode == canvas"), s);
  EXPECT_EQ(mode.en, "Switch to Canvas mode (now Camera mode)");
  EXPECT_EQ(mode.zh, "切换到画布模式（现在是相机模式）");
  s.numbers["circles_shown"] = 1;
  EXPECT_EQ(tutorialCheckWords(parseTutorialCondition("circles_shown == false"), s).en,
            "Hide the circle growth (not yet)");
  const StudyWords both = tutorialStepWords(
      {parseTutorialCondition("mode == erase"), parseTutorialCondition("erase_tool == vacuum")}, s);
  EXPECT_EQ(both.en,
            "Switch to Erase mode (now Camera mode); Choose the Vacuum erase tool (not yet)");
  EXPECT_EQ(both.zh, "切换到擦除模式（现在是相机模式）；选择吸除擦除工具（还没有）");
}

TEST(TutorialWords, ACheckTheTableCannotWordReadsTheStepsTask) {
  // A condition made by hand past the parser: a variable outside the table, a word it lacks.
  TutorialCondition unknown;
  unknown.variable = "pen_hovering";
  unknown.kind = ConditionKind::kBoolean;
  unknown.number = 1;
  EXPECT_EQ(tutorialGoalWords(unknown).en, kFallbackEn);
  EXPECT_EQ(tutorialGoalWords(unknown).zh, "完成这一步的任务");
  TutorialCondition odd_word = parseTutorialCondition("mode == light");
  odd_word.word = "sculpt";
  EXPECT_EQ(tutorialCheckWords(odd_word, {}).en, std::string(kFallbackEn) + " (not yet)");
}

TEST(TutorialWords, TheAtlasTextHoldsEveryChineseWording) {
  const std::string atlas = tutorialWordsZhText();
  for (const TutorialVariable& v : tutorialVariables())
    for (const std::string& text : everyCheck(v)) {
      const StudyWords goal = tutorialGoalWords(parseTutorialCondition(text));
      // Each Chinese character of the wording (3-byte UTF-8) is somewhere in the atlas text.
      for (size_t i = 0; i < goal.zh.size();) {
        const unsigned char c = static_cast<unsigned char>(goal.zh[i]);
        const size_t n = c < 0x80 ? 1 : c < 0xe0 ? 2 : c < 0xf0 ? 3 : 4;
        if (n > 1) {
          EXPECT_NE(atlas.find(goal.zh.substr(i, n)), std::string::npos)
              << goal.zh.substr(i, n) << " of " << goal.zh;
        }
        i += n;
      }
    }
}

}  // namespace
}  // namespace cb
