// The study protocol: the bundled thesis protocol loads with Appendix A/C's counts, its task
// order is balanced over a cycle, bad files are refused naming file, line and field.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "app/study/protocol.h"

namespace cb {
namespace {

const std::string kThesis = std::string(CB_SOURCE_DIR) + "/config/study/thesis_2014.toml";

// A small valid protocol; tests replace one line to break it.
const std::string kMinimal = R"([study]
name = "t"
[consent]
text = "ok?"
[participants]
id_scheme = "counter"
prefix = "S"
digits = 3
[[venue]]
id = "lab"
name = "Lab"
[introduction]
text = "hello"
[tutorial]
[[tutorial.step]]
instruction = "Canvas mode"
expect = ["mode == canvas"]
[free_drawing]
text = "draw"
[tasks]
order = "rotation"
[[task]]
id = "a"
title = "A"
image = "a.png"
save = ["journal"]
[questionnaire]
scale = ["no", "yes"]
[[item]]
id = "Q1"
text = "fine"
)";

std::string errorOf(const std::string& text) {
  try {
    parseStudyProtocol(text, "p.toml");
  } catch (const StudyProtocolError& e) {
    return e.what();
  }
  return "(accepted)";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(StudyProtocol, ThesisProtocolLoadsWithTheAppendicesCounts) {
  const StudyProtocol p = loadStudyProtocol(kThesis);
  EXPECT_EQ(p.tutorial.size(), 26u);  // Appendix A
  EXPECT_EQ(p.tutorial[3].expect.at(0).text(), "canvas_altitude == 96");
  EXPECT_EQ(p.tutorial[18].expect.at(0).text(), "canvas_altitude == 64");
  ASSERT_EQ(p.items.size(), 28u);  // Appendix C's 27 + lag acceptance
  EXPECT_EQ(p.items[2].id, "Q3");
  EXPECT_EQ(p.items[2].text, "*Results* in using *Pen style* is *satisfactory*.");
  EXPECT_EQ(p.items[5].text, "*Results* in using *3D Brush style* is *satisfactory*.");
  EXPECT_EQ(p.items[26].text, "The *visual affect of generated 3D cloud* is *realistic*.");
  EXPECT_EQ(p.items[27].id, "Q28");
  EXPECT_EQ(p.scale_labels.size(), 5u);
  ASSERT_EQ(p.tasks.size(), 4u);  // Appendix B
  for (const StudyTask& task : p.tasks) {
    EXPECT_DOUBLE_EQ(task.minutes, 10);  // §7.5
    EXPECT_TRUE(std::filesystem::path(task.image).is_absolute()) << task.image;
  }
  EXPECT_EQ(p.venues.size(), 2u);  // §7.4
  EXPECT_EQ(p.demographics.size(), 3u);
  EXPECT_EQ(p.constructs.size(), 4u);
  EXPECT_EQ(p.participant_ids.idFor(7), "P07");
  EXPECT_EQ(p.task_order, CounterbalanceScheme::kWilliams);
}

// Over one cycle every task is in every position equally often and (williams) every ordered
// pair of tasks is adjacent equally often.
void expectBalanced(CounterbalanceScheme scheme, int n, bool pairs) {
  const int cycle = counterbalanceCycle(scheme, n);
  std::map<std::pair<int, int>, int> at_position, follows;
  for (int participant = 1; participant <= cycle; ++participant) {
    const std::vector<int> order = taskOrderForParticipant(scheme, n, participant);
    ASSERT_EQ(std::set<int>(order.begin(), order.end()).size(), size_t(n));
    EXPECT_EQ(order, taskOrderForParticipant(scheme, n, participant + cycle));
    for (int j = 0; j < n; ++j) ++at_position[{order[j], j}];
    for (int j = 0; j + 1 < n; ++j) ++follows[{order[j], order[j + 1]}];
  }
  ASSERT_EQ(at_position.size(), size_t(n * n)) << "n=" << n;
  for (const auto& [key, count] : at_position) EXPECT_EQ(count, cycle / n) << "n=" << n;
  if (pairs) {
    ASSERT_EQ(follows.size(), size_t(n * (n - 1))) << "n=" << n;
    for (const auto& [key, count] : follows) EXPECT_EQ(count, cycle / n) << "n=" << n;
  }
}

TEST(StudyProtocol, CounterbalancingIsBalancedOverACycle) {
  for (int n = 2; n <= 7; ++n) {
    expectBalanced(CounterbalanceScheme::kRotation, n, false);
    expectBalanced(CounterbalanceScheme::kWilliams, n, true);
  }
  EXPECT_EQ(counterbalanceCycle(CounterbalanceScheme::kWilliams, 5), 10);
}

TEST(StudyProtocol, ThesisTaskOrderIsBalancedOverFourParticipants) {
  const StudyProtocol p = loadStudyProtocol(kThesis);
  EXPECT_EQ(counterbalanceCycle(p.task_order, 4), 4);
  std::map<std::pair<std::string, int>, int> at_position;
  for (int participant = 1; participant <= 4; ++participant) {
    const auto tasks = p.tasksForParticipant(participant);
    for (size_t j = 0; j < tasks.size(); ++j) ++at_position[{tasks[j]->id, int(j)}];
  }
  EXPECT_EQ(at_position.size(), 16u);
  for (const auto& [key, count] : at_position) EXPECT_EQ(count, 1);
  EXPECT_EQ(p.tasksForParticipant(1)[0]->id, "cloud1");
  EXPECT_EQ(p.tasksForParticipant(2)[0]->id, "cloud2");
}

TEST(StudyProtocol, RandomIdsAreReproducibleDistinctAndFromTheAlphabet) {
  ParticipantIdScheme scheme;
  scheme.kind = ParticipantIdScheme::Kind::kRandom;
  scheme.prefix = "X";
  scheme.seed = 42;
  std::set<std::string> seen;
  for (int n = 1; n <= 200; ++n) {
    const std::string id = scheme.idFor(n);
    ASSERT_EQ(id.size(), 7u);
    EXPECT_EQ(id.find_first_not_of(kParticipantIdAlphabet, 1), std::string::npos) << id;
    EXPECT_EQ(id, scheme.idFor(n));
    seen.insert(id);
  }
  EXPECT_EQ(seen.size(), 200u);
  const std::string first = scheme.idFor(1);
  scheme.seed = 43;
  EXPECT_NE(scheme.idFor(1), first);
}

TEST(StudyProtocol, MinimalProtocolLoadsWithDefaults) {
  const StudyProtocol p = parseStudyProtocol(kMinimal, "/study/p.toml");
  EXPECT_EQ(p.participant_ids.idFor(12), "S012");
  EXPECT_EQ(p.tasks.at(0).image, "/study/a.png");
  EXPECT_DOUBLE_EQ(p.tasks.at(0).minutes, 10);
  EXPECT_DOUBLE_EQ(p.tutorial_minutes, 10);
  EXPECT_TRUE(p.operator_required);
}

TEST(StudyProtocol, ErrorsNameFileLineAndField) {
  EXPECT_EQ(errorOf(replaced(kMinimal, "expect = [\"mode == canvas\"]",
                             "expect = [\"mode == canvass\"]")),
            "p.toml:17: tutorial.step[1].expect[1]: 'mode' cannot be 'canvass' (one of: camera, "
            "canvas, paint, erase, light)");
  EXPECT_EQ(errorOf(replaced(kMinimal, "mode == canvas", "altitude == 96")).substr(0, 43),
            "p.toml:17: tutorial.step[1].expect[1]: 'alt");
  EXPECT_EQ(errorOf(replaced(kMinimal, "order = \"rotation\"", "order = \"latin\"")),
            "p.toml:21: tasks.order: 'latin': expected \"fixed\", \"rotation\" or \"williams\"");
  EXPECT_EQ(errorOf(replaced(kMinimal, "save = [\"journal\"]", "save = [\"journal\", \"dds\"]")),
            "p.toml:26: task[1].save[2]: 'dds': expected journal, volume_vdb, volume_raw, "
            "render_exr or render_png");
  EXPECT_EQ(errorOf(replaced(kMinimal, "image = \"a.png\"\n", "")),
            "p.toml:22: task[1].image: missing (a string)");
  EXPECT_EQ(errorOf(replaced(kMinimal, "title = \"A\"", "title = \"A\"\nminutes = 0")),
            "p.toml:25: task[1].minutes: minutes must be more than 0 and at most 600");
  EXPECT_EQ(errorOf(replaced(kMinimal, "digits = 3", "digit = 3")).substr(0, 33),
            "p.toml:8: participants.digit: unk");
  EXPECT_EQ(errorOf(replaced(kMinimal, "[consent]\ntext = \"ok?\"\n", "")),
            "p.toml:1: consent: missing table");
  EXPECT_EQ(errorOf(kMinimal + "[[construct]]\nname = \"c\"\nitems = [\"Q1\", \"Q9\"]\n"),
            "p.toml:34: construct[1].items[2]: 'Q9' is not a declared [[item]] id");
  EXPECT_EQ(errorOf(kMinimal + "[[item]]\nid = \"Q1\"\ntext = \"again\"\n"),
            "p.toml:33: item[2].id: 'Q1' is already an answer column");
  EXPECT_EQ(errorOf(replaced(kMinimal, "prefix = \"S\"", "key_file = \"keys.csv\"")),
            "p.toml:7: participants.key_file: must be an absolute path, kept apart from the "
            "study data");
  EXPECT_EQ(errorOf("[study\n").rfind("p.toml:1: TOML syntax: ", 0), 0u) << errorOf("[study\n");
}

TEST(TutorialCondition, ParsesAndEvaluatesTheVocabulary) {
  TutorialState state;
  state.words["mode"] = "canvas";
  state.numbers["canvas_altitude"] = 96;
  EXPECT_TRUE(conditionHolds(parseTutorialCondition("mode == canvas"), state));
  EXPECT_FALSE(conditionHolds(parseTutorialCondition("mode != canvas"), state));
  EXPECT_TRUE(conditionHolds(parseTutorialCondition(" canvas_altitude>=96 "), state));
  EXPECT_FALSE(conditionHolds(parseTutorialCondition("canvas_altitude < 96"), state));
  EXPECT_TRUE(conditionHolds(parseTutorialCondition("canvas_altitude <= 96"), state));
  EXPECT_FALSE(conditionHolds(parseTutorialCondition("strokes >= 0"), state));  // not in state
  EXPECT_EQ(parseTutorialCondition("strokes>=1").text(), "strokes >= 1");
  EXPECT_THROW(parseTutorialCondition("mode >= canvas"), TutorialConditionError);
  EXPECT_THROW(parseTutorialCondition("strokes >= many"), TutorialConditionError);
  EXPECT_THROW(parseTutorialCondition("strokes >= 1x"), TutorialConditionError);
  EXPECT_THROW(parseTutorialCondition("cloud_empty == yes"), TutorialConditionError);
  EXPECT_THROW(parseTutorialCondition("mode canvas"), TutorialConditionError);
  EXPECT_THROW(parseTutorialCondition("Mode == canvas"), TutorialConditionError);
}

}  // namespace
}  // namespace cb
