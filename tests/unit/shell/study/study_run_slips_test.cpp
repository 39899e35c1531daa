// The study runner's screens at 1920x1080 as a participant meets them (EGL surfaceless,
// llvmpipe, the bundled thesis protocol, default brush and mapping): consent declined with a pen
// tap ends the session on a page that says so in English and Chinese, with session.json
// "declined", nothing after consent in the journal, and the loop ending by itself; a task ended
// by "I'm done" (a click asks, "Keep painting" goes back, a pen tap confirms) closes with the end
// reason `done` in trials.csv, and the taps on the panel never paint; the painter's Save
// (Ctrl+S) in a task writes into the session folder, so withdrawing the participant leaves no
// file of theirs anywhere, the state dir included.
//
// CB_KEEP_FRAMES=DIR writes each screen as slips_*.png for looking.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/core/config_paths.h"
#include "app/render/image_io.h"
#include "app/session/paint_session.h"
#include "app/session/synthetic_session.h"
#include "app/shell/painter/paint_screen.h"
#include "app/shell/study/study_run_screen.h"
#include "app/study/participant_withdrawal.h"
#include "app/study/session_trace.h"
#include "app/study/trial_table.h"
#include "drivers/replay/replay_pen_source.h"

#include "tests/support/file_text.h"
#include "tests/support/short_study.h"
#include "tests/support/test_display.h"
#include "tests/unit/shell/study/study_screen_rig.h"

namespace cb {
namespace {

constexpr int kW = 1920, kH = 1080;
constexpr int64_t kSecond = 1'000'000'000;

using cb::test::readText;

// The bundled protocol without tutorial and free drawing, one task of two minutes.
StudyProtocol slipsProtocol() {
  StudyProtocol p = loadStudyProtocol(defaultStudyProtocolPath());
  p.tutorial.clear();
  p.free_drawing = StudyStage{};
  p.tasks.resize(1);
  p.tasks[0].minutes = 2;
  return p;
}

// The runner's screen on a test display (study_screen_rig.h) with the slips' protocol.
struct Rig : test::StudyScreenRig {
  bool open(const std::string& name) {
    prepare(name);
    test::StudyRigOptions options;
    options.keep_prefix = "slips_";
    start(slipsProtocol(), options);
    return !::testing::Test::HasFatalFailure();
  }
  void pen_samples(const std::vector<PenSample>& samples, size_t per_frame) {
    pen(samples, per_frame);
  }
};

bool anyStartsWith(const std::vector<std::string>& lines, const std::string& start) {
  for (const std::string& l : lines)
    if (l.rfind(start, 0) == 0) return true;
  return false;
}

TEST(StudyRunSlips, DecliningConsentEndsTheSessionCleanly) {
  Rig rig;
  if (!rig.open("cb_study_decline_")) return;
  rig.keep("consent");
  EXPECT_TRUE(rig.shown("I agree"));
  EXPECT_TRUE(rig.shown("我同意"));
  EXPECT_TRUE(rig.shown("I do not agree"));
  EXPECT_TRUE(rig.shown("我不同意"));
  const StudyTarget* agree = rig.screen->page().find(StudyTargetAction::kAgree);
  const StudyTarget* decline = rig.screen->page().find(StudyTargetAction::kDecline);
  ASSERT_TRUE(agree && decline);
  EXPECT_FLOAT_EQ(decline->x1 - decline->x0, agree->x1 - agree->x0) << "as easy to hit";
  EXPECT_FLOAT_EQ(decline->y1 - decline->y0, agree->y1 - agree->y0);
  rig.tap(StudyTargetAction::kDecline);
  ASSERT_TRUE(rig.state->done());
  EXPECT_TRUE(rig.state->declined());
  rig.keep("declined");
  EXPECT_TRUE(rig.shown("Session ended"));
  EXPECT_TRUE(rig.shown("did not agree"));
  EXPECT_TRUE(rig.shown("您没有同意参加"));
  EXPECT_TRUE(rig.screen->page().targets.empty()) << "nothing more to tap";
  EXPECT_NE(readText(rig.folder + "/session.json").find("\"status\": \"declined\""),
            std::string::npos)
      << readText(rig.folder + "/session.json");
  const std::vector<std::string> markers = rig.markers();
  EXPECT_TRUE(anyStartsWith(markers, "study.consent agreed=no participant=P01"));
  EXPECT_TRUE(anyStartsWith(markers, "study.end declined"));
  EXPECT_FALSE(anyStartsWith(markers, "study.stage-begin stage=participant"));
  EXPECT_EQ(rig.session->strokesMapped(), 0u) << "the tap never painted";
  rig.frames(4, 400'000'000);  // the closing page shows end_seconds (1 s), then the loop ends
  EXPECT_EQ(rig.quit, "consent declined");
  EXPECT_FALSE(std::filesystem::exists(rig.folder + "/tasks")) << "no task data";
  EXPECT_FALSE(std::filesystem::exists(rig.folder + "/questionnaire.csv")) << "no answer rows";
  EXPECT_FALSE(std::filesystem::exists(rig.folder + "/demographics.csv"));
}

TEST(StudyRunSlips, ImDoneEndsTheTaskWithEndReasonDone) {
  Rig rig;
  if (!rig.open("cb_study_done_")) return;
  rig.frames(1);
  rig.tap(StudyTargetAction::kAgree);
  rig.tap(StudyTargetAction::kContinue);
  if (rig.state->stage() == StudyStageKind::kIntroduction) rig.tap(StudyTargetAction::kContinue);
  ASSERT_EQ(rig.state->stage(), StudyStageKind::kTask) << rig.state->waitingFor(rig.now);
  rig.frames(2);

  // One stroke on the canvas, then the task panel's "I'm done".
  const SyntheticStroke stroke = referencePaintStrokes(kW, kH)[0];
  rig.pen_samples(syntheticPenSamples(stroke, rig.tablet, kW, kH, 200.0, rig.now), 24);
  ASSERT_EQ(rig.session->strokesMapped(), 1u);
  rig.keep("task");
  EXPECT_TRUE(rig.shown("I'm done"));
  EXPECT_TRUE(rig.shown("我画完了"));
  EXPECT_TRUE(rig.shown("Tap \"I'm done\" when finished"));
  // Clicked: the panel asks; "Keep painting" goes back to the task.
  rig.click(StudyTargetAction::kDone);
  rig.keep("task_done_asked");
  EXPECT_TRUE(rig.shown("Finish this task now?"));
  EXPECT_TRUE(rig.screen->page().find(StudyTargetAction::kDoneConfirm));
  EXPECT_FALSE(rig.state->closing()) << "one tap does not end a task";
  rig.click(StudyTargetAction::kDoneCancel);
  EXPECT_TRUE(rig.screen->page().find(StudyTargetAction::kDone));
  EXPECT_EQ(rig.state->stage(), StudyStageKind::kTask);
  // With the pen: asked, then confirmed.
  rig.frames(1, 30 * kSecond);
  rig.tap(StudyTargetAction::kDone);
  ASSERT_TRUE(rig.screen->page().find(StudyTargetAction::kDoneConfirm));
  rig.tap(StudyTargetAction::kDoneConfirm);
  rig.frames(3);
  EXPECT_EQ(rig.session->strokesMapped(), 1u) << "the panel's taps never paint";
  ASSERT_EQ(rig.state->stage(), StudyStageKind::kDemographics) << rig.state->waitingFor(rig.now);
  rig.keep("after_done");

  const std::vector<std::string> markers = rig.markers();
  EXPECT_TRUE(
      anyStartsWith(markers, "study.stage-closing stage=task task=cloud1 position=1 why=done"));
  const std::vector<TrialRow> trials =
      trialsOfSession(loadSessionTrace(rig.folder + "/session.cbj"));
  ASSERT_EQ(trials.size(), 1u);
  EXPECT_EQ(trials[0].end_reason, "done");
  ASSERT_TRUE(trials[0].duration_s);
  EXPECT_GT(*trials[0].duration_s, 30.0) << "the 30 s the test's clock ran";
  EXPECT_LT(*trials[0].duration_s, 120.0) << "ended before its two minutes";
  EXPECT_EQ(trials[0].strokes, 1);
  EXPECT_TRUE(std::filesystem::exists(rig.folder + "/tasks/cloud1.cbvol")) << "saved as at time up";

  // On to the questionnaire (demographics skipped): the item in English over Chinese.
  while (rig.state->stage() == StudyStageKind::kDemographics)
    ASSERT_NO_FATAL_FAILURE(rig.tap(StudyTargetAction::kSkipField));
  ASSERT_EQ(rig.state->stage(), StudyStageKind::kQuestionnaire);
  rig.keep("questionnaire");
  EXPECT_TRUE(rig.shown("使用钢笔风格绘制笔触容易使用。")) << "Q1 in Chinese, without the marks";
  EXPECT_TRUE(rig.shown("非常同意"));
}

// Regular files under `dir`, at any depth.
std::vector<std::string> filesUnder(const std::string& dir) {
  std::vector<std::string> files;
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(dir, ec);
       it != std::filesystem::recursive_directory_iterator(); ++it)
    if (it->is_regular_file()) files.push_back(it->path().string());
  return files;
}

TEST(StudyRunSlips, ASaveInATaskStaysInTheSessionAndIsWithdrawnWithIt) {
  Rig rig;
  if (!rig.open("cb_study_save_")) return;
  rig.frames(1);
  rig.tap(StudyTargetAction::kAgree);
  rig.tap(StudyTargetAction::kContinue);
  if (rig.state->stage() == StudyStageKind::kIntroduction) rig.tap(StudyTargetAction::kContinue);
  ASSERT_EQ(rig.state->stage(), StudyStageKind::kTask) << rig.state->waitingFor(rig.now);
  rig.frames(2);
  const SyntheticStroke stroke = referencePaintStrokes(kW, kH)[0];
  rig.pen_samples(syntheticPenSamples(stroke, rig.tablet, kW, kH, 200.0, rig.now), 24);
  ASSERT_EQ(rig.session->strokesMapped(), 1u);
  rig.screen->onCommand(Command::kSave, rig.now);  // Ctrl+S
  rig.frames(2);

  const std::vector<std::string> saved = filesUnder(rig.folder + "/saved");
  ASSERT_EQ(saved.size(), 1u) << "the cloud saved into the session folder";
  EXPECT_EQ(std::filesystem::path(saved[0]).extension(), ".vol");
  EXPECT_EQ(rig.screen->paintScreen().lastSaved(), saved[0]);
  for (const std::string& f : filesUnder(rig.dir + "/state"))
    ADD_FAILURE() << "the study wrote into the state dir: " << f;

  // Withdrawn: the participant's session folder goes, saved cloud and all; what the runner
  // wrote is all the participant's, so nothing is left under the data or the state dir.
  const WithdrawalResult withdrawn =
      withdrawParticipant(rig.dir + "/data", rig.state->participantId(), {}, false);
  EXPECT_EQ(withdrawn.removed_paths.size(), 1u);
  EXPECT_TRUE(withdrawn.still_mentioning.empty());
  for (const std::string& f : filesUnder(rig.dir))
    ADD_FAILURE() << "left after the withdrawal: " << f;
}

// A task whose own files cannot be written when it ends (tasks/ is a file: a real error from
// the file system): the operator's band names the files waiting, the participant goes on, and
// once the obstacle is gone the files appear within the second's retry and the band goes.
TEST(StudyRunSlips, TaskFilesThatCannotBeWrittenAreNamedAndWrittenLater) {
  Rig rig;
  if (!rig.open("cb_study_task_retry_")) return;
  rig.frames(1);
  rig.tap(StudyTargetAction::kAgree);
  rig.tap(StudyTargetAction::kContinue);
  if (rig.state->stage() == StudyStageKind::kIntroduction) rig.tap(StudyTargetAction::kContinue);
  ASSERT_EQ(rig.state->stage(), StudyStageKind::kTask) << rig.state->waitingFor(rig.now);
  rig.frames(2);
  const SyntheticStroke stroke = referencePaintStrokes(kW, kH)[0];
  rig.pen_samples(syntheticPenSamples(stroke, rig.tablet, kW, kH, 200.0, rig.now), 24);
  ASSERT_EQ(rig.session->strokesMapped(), 1u);
  // The task's volume as it goes (written at the stroke's end), then taken away and the
  // folder's place taken by a file.
  EXPECT_TRUE(std::filesystem::exists(rig.folder + "/tasks/cloud1.cbvol"));
  std::filesystem::remove_all(rig.folder + "/tasks");
  std::ofstream(rig.folder + "/tasks") << "in the way";
  rig.tap(StudyTargetAction::kDone);
  rig.tap(StudyTargetAction::kDoneConfirm);
  rig.frames(3);
  ASSERT_EQ(rig.state->stage(), StudyStageKind::kDemographics) << rig.state->waitingFor(rig.now);
  rig.keep("task_files_waiting");
  EXPECT_TRUE(rig.shown("OPERATOR: the session folder cannot be written"));
  EXPECT_TRUE(rig.shown("waiting to be written: tasks/cloud1.{"));
  EXPECT_FALSE(std::filesystem::is_directory(rig.folder + "/tasks"));
  std::filesystem::remove(rig.folder + "/tasks");
  rig.frames(3, 400'000'000);  // past the next retry
  EXPECT_FALSE(rig.shown("OPERATOR:")) << "the band goes once all is written";
  EXPECT_TRUE(std::filesystem::exists(rig.folder + "/tasks/cloud1.cbvol"));
  const std::vector<std::string> markers = rig.markers();
  bool written = false;
  for (const std::string& m : markers)
    written = written || (m.rfind("study.files-written files=", 0) == 0 &&
                          m.find("tasks/cloud1.cbvol") != std::string::npos);
  EXPECT_TRUE(written) << "the late write is journalled";
}

}  // namespace
}  // namespace cb
