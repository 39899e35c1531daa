// The study runner's state machine (app/study/study_run_state.h) over the bundled thesis
// protocol, headless, with a made-up clock: every stage in order, each of Appendix A's 26 steps
// advancing only when its check holds, the timed stages ending at their limits (the clock
// stopped while paused), the operator's pause, skip and abort with reasons, and the answers
// written as the CSVs `study report` reads.
#include <gtest/gtest.h>

#include <sstream>

#include "app/study/likert_answers.h"
#include "app/study/protocol.h"
#include "app/study/study_run_state.h"

namespace cb {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

// A session state in which `c` holds.
void satisfy(const TutorialCondition& c, TutorialState* s) {
  if (c.kind == ConditionKind::kWord) {
    if (c.op == ConditionOperator::kEqual) s->words[c.variable] = c.word;
    return;
  }
  int64_t v = c.number;
  if (c.op == ConditionOperator::kGreater) v += 1;
  if (c.op == ConditionOperator::kLess) v -= 1;
  if (c.op == ConditionOperator::kNotEqual) v += 1;
  s->numbers[c.variable] = v;
}

bool hasRecord(const std::vector<StudyRunRecord>& records, const std::string& part) {
  for (const StudyRunRecord& r : records)
    if (r.text.find(part) != std::string::npos) return true;
  return false;
}

TEST(StudyRunState, TheThesisStudyRunsThroughEveryStageInOrder) {
  const StudyProtocol p = loadStudyProtocol(defaultStudyProtocolPath());
  int64_t t = 100 * kSecond;
  StudyRunState s(p, 3, t);
  std::vector<StudyRunRecord> records;
  const auto take = [&] {
    for (StudyRunRecord& r : s.takeRecords()) records.push_back(r);
  };
  EXPECT_EQ(s.participantId(), "P03");
  EXPECT_EQ(s.stage(), StudyStageKind::kConsent);
  EXPECT_NE(s.waitingFor(t).find("I agree"), std::string::npos);
  s.proceed(t);  // Continue is not consent
  EXPECT_EQ(s.stage(), StudyStageKind::kConsent);
  s.agree(t += kSecond);
  EXPECT_EQ(s.stage(), StudyStageKind::kParticipant);
  EXPECT_NE(s.waitingFor(t).find("P03"), std::string::npos);
  s.proceed(t += kSecond);
  EXPECT_EQ(s.stage(), StudyStageKind::kIntroduction);
  s.proceed(t += kSecond);
  ASSERT_EQ(s.stage(), StudyStageKind::kTutorial);

  // Appendix A: a state that satisfies every step but the current one never advances it; the
  // step's own check does.
  for (size_t i = 0; i < p.tutorial.size(); ++i) {
    ASSERT_EQ(s.tutorialStep(), int(i));
    EXPECT_FALSE(s.observeTutorial(TutorialState{}, t += kSecond)) << "step " << i + 1;
    TutorialState state;
    for (const TutorialCondition& c : p.tutorial[i].expect) satisfy(c, &state);
    EXPECT_TRUE(s.observeTutorial(state, t += kSecond)) << "step " << i + 1;
  }
  EXPECT_TRUE(s.closing()) << "the last step closes the tutorial";
  s.closeStage(t);
  ASSERT_EQ(s.stage(), StudyStageKind::kFreeDrawing);
  EXPECT_DOUBLE_EQ(s.stageLimitSeconds(), 600.0);
  s.tick(t += 599 * kSecond);
  EXPECT_FALSE(s.closing());
  EXPECT_DOUBLE_EQ(s.secondsLeft(t), 1.0);
  s.tick(t += kSecond);
  ASSERT_TRUE(s.closing());
  EXPECT_EQ(s.closingWhy(), "time up");
  s.closeStage(t);

  // Four tasks in participant 3's Williams order, each ending at its 10 minutes.
  const std::vector<const StudyTask*> order = p.tasksForParticipant(3);
  for (size_t i = 0; i < order.size(); ++i) {
    ASSERT_EQ(s.stage(), StudyStageKind::kTask);
    EXPECT_EQ(s.task(), order[i]);
    EXPECT_EQ(s.position().order, int(i));
    s.tick(t += 601 * kSecond);
    ASSERT_TRUE(s.closing());
    s.closeStage(t, {"tasks/" + order[i]->id + ".vdb"});
  }
  ASSERT_EQ(s.stage(), StudyStageKind::kDemographics);
  EXPECT_EQ(s.answerField("old", t), "enter a whole number from 16 to 99");
  EXPECT_EQ(s.answerField("12", t), "enter a whole number from 16 to 99");
  EXPECT_EQ(s.fieldIndex(), 0);
  EXPECT_EQ(s.answerField(" 34 ", t += kSecond), "");
  EXPECT_EQ(s.answerField("female", t += kSecond), "");
  s.skipField(t += kSecond);
  ASSERT_EQ(s.stage(), StudyStageKind::kQuestionnaire);
  ASSERT_EQ(p.items.size(), 28u) << "Appendix C's 27 items and the lag item";
  for (size_t i = 0; i < p.items.size(); ++i) {
    EXPECT_EQ(s.itemIndex(), int(i));
    if (i == 4) {
      s.skipItem(t += kSecond);
      continue;
    }
    s.answerItem(0, t);  // off the scale: ignored
    s.answerItem(int(i % 5) + 1, t += kSecond);
  }
  ASSERT_EQ(s.stage(), StudyStageKind::kFreeText);
  s.answerFreeText("the lag, \"sometimes\"", t += kSecond);
  ASSERT_TRUE(s.done());
  EXPECT_FALSE(s.aborted());
  take();

  // The answers as `study report` reads them.
  std::istringstream csv(s.questionnaireCsv());
  const LikertAnswers answers = readLikertAnswers(csv, "questionnaire.csv");
  ASSERT_EQ(answers.participants, std::vector<std::string>{"P03"});
  ASSERT_EQ(answers.items.size(), 28u);
  EXPECT_EQ(answers.items[27], "Q28");
  for (size_t i = 0; i < 28; ++i) {
    if (i == 4)
      EXPECT_FALSE(answers.answers[0][i].has_value());
    else
      EXPECT_EQ(answers.answers[0][i], int(i % 5) + 1) << "item " << i + 1;
  }
  EXPECT_EQ(s.demographicsCsv(),
            "participant,age,gender,modelling_experience,feedback\n"
            "P03,34,female,NA,\"the lag, \"\"sometimes\"\"\"\n");
  EXPECT_TRUE(hasRecord(records, "study.session protocol="));
  EXPECT_TRUE(hasRecord(records, "study.stage-begin stage=consent"));
  EXPECT_TRUE(hasRecord(records, "study.consent agreed=yes participant=P03"));
  EXPECT_TRUE(hasRecord(records, "study.tutorial-step done step=26"));
  EXPECT_TRUE(hasRecord(records, "study.stage-closing stage=task task=" + order[3]->id +
                                     " position=4 why=\"time up\""));
  EXPECT_TRUE(hasRecord(records, "study.saved stage=task task=" + order[0]->id));
  EXPECT_TRUE(hasRecord(records, "study.answer item=Q28 value=3"));
  EXPECT_TRUE(hasRecord(records, "study.answer item=Q5 value=NA"));
  EXPECT_TRUE(hasRecord(records, "study.end completed"));
}

TEST(StudyRunState, OperatorPausesSkipsAndAbortsWithReasons) {
  const StudyProtocol p = loadStudyProtocol(defaultStudyProtocolPath());
  int64_t t = 0;
  StudyRunState s(p, 1, t);
  s.agree(t);
  s.proceed(t);
  // Skip the introduction (digit 2: "participant is stuck"), then a tutorial step.
  s.requestOperator(OperatorAction::kSkip, t += kSecond);
  ASSERT_TRUE(s.choosing());
  EXPECT_NE(s.waitingFor(t).find("choose why to skip"), std::string::npos);
  s.proceed(t);  // the participant's buttons wait while the operator chooses
  EXPECT_EQ(s.stage(), StudyStageKind::kIntroduction);
  s.chooseReason(1, t);
  ASSERT_EQ(s.stage(), StudyStageKind::kTutorial);
  s.requestOperator(OperatorAction::kSkip, t);
  s.chooseReason(0, t);
  EXPECT_EQ(s.tutorialStep(), 1) << "a skip in the tutorial skips one step";
  // Cancel leaves everything as it was.
  s.requestOperator(OperatorAction::kAbort, t);
  s.cancelChoice(t);
  EXPECT_FALSE(s.choosing());
  EXPECT_FALSE(s.done());
  for (int i = 1; i < int(p.tutorial.size()); ++i) {
    s.requestOperator(OperatorAction::kSkip, t);
    s.chooseReason(3, t);
  }
  ASSERT_TRUE(s.closing());
  s.closeStage(t);
  ASSERT_EQ(s.stage(), StudyStageKind::kFreeDrawing);
  s.tick(t += 100 * kSecond);
  EXPECT_DOUBLE_EQ(s.secondsLeft(t), 500.0);
  // Paused: the clock stops, also while the reason is chosen.
  s.requestOperator(OperatorAction::kPause, t);
  s.tick(t += 30 * kSecond);
  s.chooseReason(1, t);
  EXPECT_TRUE(s.paused());
  EXPECT_EQ(s.pauseReason(), "participant needs a break");
  s.tick(t += 1000 * kSecond);
  EXPECT_FALSE(s.closing()) << "no time passes while paused";
  EXPECT_DOUBLE_EQ(s.secondsLeft(t), 500.0);
  s.requestOperator(OperatorAction::kPause, t);  // resume
  EXPECT_FALSE(s.paused());
  s.tick(t += 10 * kSecond);
  EXPECT_DOUBLE_EQ(s.secondsLeft(t), 490.0);
  // Skip the free drawing: it closes (the runner saves), then the first task.
  s.requestOperator(OperatorAction::kSkip, t);
  s.chooseReason(0, t);
  ASSERT_TRUE(s.closing());
  EXPECT_EQ(s.closingWhy(), "skipped: participant finished early");
  s.closeStage(t);
  ASSERT_EQ(s.stage(), StudyStageKind::kTask);
  // Abort in a task: the task still closes (its files are saved), then the session ends.
  s.requestOperator(OperatorAction::kAbort, t += kSecond);
  s.chooseReason(0, t);
  ASSERT_TRUE(s.closing());
  s.closeStage(t, {"session.cbj"});
  EXPECT_TRUE(s.done());
  EXPECT_TRUE(s.aborted());
  EXPECT_EQ(s.abortReason(), "participant withdrew");
  const std::vector<StudyRunRecord> records = s.takeRecords();
  EXPECT_TRUE(hasRecord(records,
                        "study.operator action=skip reason=\"participant is stuck\" "
                        "stage=introduction"));
  EXPECT_TRUE(hasRecord(records, "study.tutorial-step skipped step=1"));
  EXPECT_TRUE(hasRecord(records, "study.operator-cancel action=abort"));
  EXPECT_TRUE(hasRecord(records,
                        "study.operator action=pause reason=\"participant needs a "
                        "break\" stage=free-drawing"));
  EXPECT_TRUE(hasRecord(records, "study.operator action=resume stage=free-drawing"));
  EXPECT_TRUE(hasRecord(records,
                        "study.operator action=abort reason=\"participant withdrew\" "
                        "stage=task"));
  EXPECT_TRUE(hasRecord(records, "study.saved stage=task"));
  EXPECT_TRUE(hasRecord(records, "study.end aborted reason=\"participant withdrew\""));
  // Nothing was answered: every item NA.
  std::istringstream csv(s.questionnaireCsv());
  const LikertAnswers answers = readLikertAnswers(csv, "questionnaire.csv");
  for (const auto& a : answers.answers[0]) EXPECT_FALSE(a.has_value());
}

// What a restored state must agree on with the original at time t.
std::string snapshot(const StudyRunState& s, int64_t t) {
  std::ostringstream o;
  o << studyStageName(s.stage()) << " task=" << (s.task() ? s.task()->id : "-")
    << " step=" << s.tutorialStep() << " item=" << s.itemIndex() << " field=" << s.fieldIndex()
    << " text=" << s.freeTextIndex() << " paused=" << s.paused() << " choosing=" << s.choosing()
    << " closing=" << s.closingWhy() << " seconds=" << s.stageSeconds(t)
    << " aborted=" << s.aborted() << "\n"
    << s.questionnaireCsv() << s.demographicsCsv();
  for (const std::string& name : s.stagesCompleted()) o << name << ",";
  for (const auto& text : s.freeTextAnswers()) o << "\nfree text: " << text.value_or("<none>");
  return o.str();
}

// Resuming: a state restored from any prefix of a session's records is the state the
// session was in when it wrote them, and the records it made but the journal lost are made again.
TEST(StudyRunState, RestoredFromItsRecordsTheSessionCarriesOnWhereItWas) {
  StudyProtocol p = loadStudyProtocol(defaultStudyProtocolPath());
  int64_t t = 100 * kSecond;
  StudyRunState s(p, 3, t);
  std::vector<StudyRunRecord> records;
  struct Checkpoint {
    size_t records;
    int64_t t;
    std::string state;
  };
  std::vector<Checkpoint> checkpoints;
  const auto step = [&] {
    for (StudyRunRecord& r : s.takeRecords()) records.push_back(r);
    checkpoints.push_back({records.size(), t, snapshot(s, t)});
  };
  step();
  s.agree(t += kSecond), step();
  s.proceed(t += kSecond), step();
  s.requestOperator(OperatorAction::kSkip, t += kSecond), step();  // the introduction
  s.chooseReason(1, t += kSecond), step();
  for (size_t i = 0; i < p.tutorial.size(); ++i) {
    if (i == 3) {
      s.requestOperator(OperatorAction::kAbort, t += kSecond), step();
      s.cancelChoice(t += kSecond), step();
      s.requestOperator(OperatorAction::kSkip, t += kSecond), step();
      s.chooseReason(2, t += kSecond), step();
      continue;
    }
    TutorialState state;
    for (const TutorialCondition& c : p.tutorial[i].expect) satisfy(c, &state);
    s.observeTutorial(state, t += 3 * kSecond), step();
  }
  s.closeStage(t += kSecond), step();
  ASSERT_EQ(s.stage(), StudyStageKind::kFreeDrawing);
  s.tick(t += 100 * kSecond), step();
  s.requestOperator(OperatorAction::kPause, t += kSecond), step();
  s.chooseReason(0, t += 5 * kSecond), step();
  s.requestOperator(OperatorAction::kPause, t += 60 * kSecond), step();  // resume
  t += 3600 * kSecond;
  s.resumedAfter(t - 3600 * kSecond, t), step();  // the runner was down an hour
  EXPECT_DOUBLE_EQ(s.secondsLeft(t), 499.0) << "neither the pause nor the hour down counts";
  s.tick(t += 600 * kSecond), step();  // time up
  ASSERT_TRUE(s.closing());
  s.closeStage(t += kSecond), step();
  for (int i = 0; i < s.taskCount(); ++i) {
    ASSERT_EQ(s.stage(), StudyStageKind::kTask);
    s.tick(t += 601 * kSecond), step();
    s.closeStage(t += kSecond, {"session.cbj", "tasks/" + s.task()->id + ".vdb"}), step();
  }
  ASSERT_EQ(s.answerField("29", t += kSecond), ""), step();
  s.skipField(t += kSecond), step();
  ASSERT_EQ(s.answerField("a lot, \"really\"", t += kSecond), ""), step();
  for (size_t i = 0; i < p.items.size(); ++i) {
    if (i == 6) s.previousItem(t), s.answerItem(5, t += kSecond), step();  // Q6 changed
    if (i == 9)
      s.skipItem(t += kSecond), step();
    else
      s.answerItem(int(i % 5) + 1, t += kSecond), step();
  }
  s.answerFreeText("NA", t += kSecond), step();  // typed: not a missing answer
  ASSERT_TRUE(s.done());

  for (const Checkpoint& c : checkpoints) {
    StudyRunState restored(p, 3, records.front().t_ns);
    const std::vector<StudyRunRecord> prefix(records.begin(), records.begin() + long(c.records));
    std::string error;
    ASSERT_TRUE(restored.restore(prefix, &error)) << error;
    EXPECT_EQ(snapshot(restored, c.t), c.state) << "after " << c.records << " records";
    EXPECT_TRUE(restored.takeRecords().empty()) << "a whole journal leaves nothing to make";
  }
  // A journal cut between the records one input made: restored, those are made again.
  for (size_t cut = 1; cut < records.size(); ++cut) {
    StudyRunState restored(p, 3, records.front().t_ns);
    std::string error;
    ASSERT_TRUE(restored.restore({records.begin(), records.begin() + long(cut)}, &error)) << error;
    const std::vector<StudyRunRecord> again = restored.takeRecords();
    for (size_t i = 0; i < again.size(); ++i) {
      ASSERT_LT(cut + i, records.size());
      EXPECT_EQ(again[i].text, records[cut + i].text) << "cut at " << cut;
    }
  }
  // The answers as given (Q6 changed, Q10 skipped, the free text the word NA).
  const std::string& last = checkpoints.back().state;
  EXPECT_NE(last.find("P03,1,2,3,4,5,5,2,3,4,NA,1,"), std::string::npos) << last;
  EXPECT_NE(last.find("P03,29,NA,\"a lot, \"\"really\"\"\","), std::string::npos) << last;
  EXPECT_NE(last.find("free text: NA"), std::string::npos) << last;

  // Another participant's journal (another task order), or another protocol, is refused.
  StudyRunState other(p, 4, records.front().t_ns);
  std::string error;
  EXPECT_FALSE(other.restore(records, &error));
  EXPECT_NE(error.find("study record 1"), std::string::npos) << error;
  StudyProtocol renamed = p;
  renamed.version = "2099.1";
  StudyRunState elsewhere(renamed, 3, records.front().t_ns);
  EXPECT_FALSE(elsewhere.restore(records, &error));
  // A record the runner never makes is named.
  size_t at_participant = 0;
  while (records[at_participant].text.rfind("study.stage-begin stage=participant", 0) != 0)
    ++at_participant;
  std::vector<StudyRunRecord> forged(records.begin(), records.begin() + long(at_participant) + 1);
  forged.push_back({t, "study.answer item=Q1 value=5"});  // at the participant page
  StudyRunState forged_state(p, 3, records.front().t_ns);
  EXPECT_FALSE(forged_state.restore(forged, &error));
  EXPECT_NE(error.find("does not apply here"), std::string::npos) << error;
}

}  // namespace
}  // namespace cb
