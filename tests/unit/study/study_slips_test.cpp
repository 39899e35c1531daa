// A participant's and an operator's slips in the study runner, headless (the state machine over
// the bundled thesis protocol with a made-up clock, the session folder record): consent
// declined ends the session with nothing after consent; a task ended by the participant's
// "I'm done" closes with the end reason `done`; both come back the same from their journal
// records (resume, replay); a participant's existing session folders are found (so the runner
// refuses a second first session of one participant).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "app/study/protocol.h"
#include "app/study/study_run_state.h"
#include "app/study/study_session_record.h"
#include "app/study/trial_table.h"

namespace cb {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

std::vector<std::string> texts(const std::vector<StudyRunRecord>& records) {
  std::vector<std::string> out;
  for (const StudyRunRecord& r : records) out.push_back(r.text);
  return out;
}

TEST(StudySlips, DecliningConsentEndsTheSessionThereAndResumesTheSame) {
  const StudyProtocol p = loadStudyProtocol(defaultStudyProtocolPath());
  const int64_t t0 = 100 * kSecond;
  StudyRunState s(p, 2, t0);
  EXPECT_NE(s.waitingFor(t0).find("I do not agree"), std::string::npos) << s.waitingFor(t0);
  s.decline(t0 + 4 * kSecond);
  EXPECT_TRUE(s.done());
  EXPECT_TRUE(s.declined());
  EXPECT_FALSE(s.aborted());
  EXPECT_NE(s.waitingFor(t0).find("did not agree"), std::string::npos) << s.waitingFor(t0);
  const std::vector<StudyRunRecord> records = s.takeRecords();
  ASSERT_FALSE(records.empty());
  EXPECT_EQ(records[0].text.rfind("study.session ", 0), 0u) << records[0].text;
  const std::vector<std::string> expected = {
      records[0].text, "study.stage-begin stage=consent", "study.consent agreed=no participant=P02",
      "study.stage-end stage=consent how=declined", "study.end declined"};
  EXPECT_EQ(texts(records), expected);
  // No stage after consent began, and no answer is recorded.
  for (const StudyRunRecord& r : records) {
    EXPECT_EQ(r.text.find("stage=participant"), std::string::npos) << r.text;
    EXPECT_EQ(r.text.find("study.answer"), std::string::npos) << r.text;
  }
  EXPECT_EQ(s.questionnaireCsv().find("P02,NA"), s.questionnaireCsv().find('\n') + 1);
  // Agreeing after declining does nothing: the session is over.
  s.agree(t0 + 5 * kSecond);
  EXPECT_TRUE(s.takeRecords().empty());

  // A restarted runner reads the same state back from the journal's records.
  StudyRunState again(p, 2, t0);
  std::string error;
  ASSERT_TRUE(again.restore(records, &error)) << error;
  EXPECT_TRUE(again.done());
  EXPECT_TRUE(again.declined());
  EXPECT_TRUE(again.takeRecords().empty()) << "nothing lost, nothing to write again";
}

TEST(StudySlips, ConsentGivenReadsAsBeforeInAnOldJournal) {
  // `agreed=yes` records (every journal written before declining existed) restore as agreement.
  const StudyProtocol p = loadStudyProtocol(defaultStudyProtocolPath());
  StudyRunState s(p, 1, 0);
  s.agree(kSecond);
  const std::vector<StudyRunRecord> records = s.takeRecords();
  StudyRunState again(p, 1, 0);
  std::string error;
  ASSERT_TRUE(again.restore(records, &error)) << error;
  EXPECT_EQ(again.stage(), StudyStageKind::kParticipant);
  EXPECT_FALSE(again.declined());
}

// A state at the start of its first task (tutorial and free drawing skipped by the operator).
void toFirstTask(StudyRunState& s, int64_t* t) {
  s.agree(*t += kSecond);
  s.proceed(*t += kSecond);
  s.proceed(*t += kSecond);
  while (s.stage() != StudyStageKind::kTask) {
    s.requestOperator(OperatorAction::kSkip, *t += kSecond);
    s.chooseReason(0, *t);
    if (s.closing()) s.closeStage(*t);
  }
}

TEST(StudySlips, ImDoneClosesTheTaskWithEndReasonDone) {
  const StudyProtocol p = loadStudyProtocol(defaultStudyProtocolPath());
  int64_t t = 100 * kSecond;
  StudyRunState s(p, 1, t);
  s.finishTask(t);  // not in a task: nothing happens
  EXPECT_EQ(s.stage(), StudyStageKind::kConsent);
  toFirstTask(s, &t);
  const std::string first = s.task()->id;
  EXPECT_NE(s.waitingFor(t).find("I'm done"), std::string::npos) << s.waitingFor(t);
  // Paused, the participant cannot end the task.
  s.requestOperator(OperatorAction::kPause, t += kSecond);
  s.chooseReason(0, t);
  s.finishTask(t += kSecond);
  EXPECT_FALSE(s.closing());
  s.requestOperator(OperatorAction::kPause, t += 10 * kSecond);  // resume
  s.finishTask(t += 95 * kSecond);
  ASSERT_TRUE(s.closing());
  EXPECT_EQ(s.closingWhy(), "done");
  EXPECT_EQ(trialEndReason(s.closingWhy()), "done");
  const double seconds = s.stageSeconds(t);
  EXPECT_NEAR(seconds, 96.0, 1e-9) << "95 s painting + 1 s before the pause; the pause not counted";
  s.closeStage(t, {"tasks/" + first + ".cbvol"});
  ASSERT_EQ(s.stage(), StudyStageKind::kTask);
  EXPECT_NE(s.task()->id, first) << "the next task";
  const std::vector<StudyRunRecord> records = s.takeRecords();
  bool closing_done = false;
  for (const StudyRunRecord& r : records)
    closing_done =
        closing_done || (r.text.rfind("study.stage-closing stage=task task=" + first, 0) == 0 &&
                         r.text.find(" why=done seconds=96") != std::string::npos);
  EXPECT_TRUE(closing_done);

  StudyRunState again(p, 1, 100 * kSecond);
  std::string error;
  ASSERT_TRUE(again.restore(records, &error)) << error;
  EXPECT_EQ(again.task()->id, s.task()->id);
  EXPECT_EQ(again.stagesCompleted(), s.stagesCompleted());
}

TEST(StudySlips, AParticipantsSessionFoldersAreFound) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("cb_slips_" + std::to_string(::getpid())))
          .string();
  std::filesystem::remove_all(dir);
  EXPECT_TRUE(participantSessionFolders(dir, "P01").empty()) << "no data directory yet";
  std::filesystem::create_directories(dir + "/P01-20261129T100000Z");
  std::filesystem::create_directories(dir + "/P01-20261129T090000Z");
  std::filesystem::create_directories(dir + "/P010-20261129T090000Z");  // another participant
  std::ofstream(dir + "/P02-notes.txt") << "a file, not a session folder";
  const std::vector<std::string> folders = participantSessionFolders(dir, "P01");
  ASSERT_EQ(folders.size(), 2u);
  EXPECT_EQ(folders[0], dir + "/P01-20261129T090000Z");
  EXPECT_EQ(folders[1], dir + "/P01-20261129T100000Z");
  EXPECT_TRUE(participantSessionFolders(dir, "P02").empty());
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cb
