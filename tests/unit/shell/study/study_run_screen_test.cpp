// `cloudbrush study run`'s screens (app/shell/study/study_run_screen.h) driven the way the frame
// loop drives them, on EGL surfaceless (llvmpipe) with the product's defaults (the bundled thesis
// protocol, its consent text, demographics, 28 questionnaire items and its first task's picture;
// default brush and mapping configs), and a clock the test moves. Pen taps and strokes are raw
// samples of the synthetic tablet through the real calibration, pen events and screens.
// The protocol is the bundled one shortened: five of Appendix A's steps, no free drawing, one
// task of one minute.
//
// CB_KEEP_FRAMES=DIR writes each runner screen as study_*.png for looking.
#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/brush/synthetic_strokes.h"
#include "app/core/config_paths.h"
#include "app/render/image_io.h"
#include "app/session/paint_session.h"
#include "app/session/session_replay.h"
#include "app/session/synthetic_session.h"
#include "app/shell/keymap.h"
#include "app/shell/painter/paint_screen.h"
#include "app/shell/study/study_run_screen.h"
#include "app/study/likert_answers.h"
#include "app/study/session_trace.h"
#include "app/study/trace_csv.h"
#include "drivers/replay/replay_pen_source.h"

#include "tests/support/file_text.h"
#include "tests/support/test_display.h"
#include "tests/unit/shell/study/study_screen_rig.h"

namespace cb {
namespace {

constexpr int kW = 640, kH = 360;
constexpr int64_t kSecond = 1'000'000'000;

using cb::test::readText;

// The bundled protocol, shortened (see the file comment).
StudyProtocol shortThesisProtocol() {
  StudyProtocol p = loadStudyProtocol(defaultStudyProtocolPath());
  std::vector<TutorialStep> steps;
  for (int i : {1, 2, 6, 7, 8}) steps.push_back(p.tutorial[size_t(i)]);
  p.tutorial = steps;  // R, 2, 3, B, a stroke
  p.free_drawing = StudyStage{};
  p.free_drawing.text.clear();
  p.free_drawing.minutes = 0;
  p.tasks.resize(1);
  p.tasks[0].minutes = 1;
  return p;
}

// The runner on a 640x360 test display (study_screen_rig.h) with the shortened protocol;
// `protocol` may be changed before open().
struct Rig : test::StudyScreenRig {
  Rig() { protocol = shortThesisProtocol(); }
  MappingConfig mapping = loadMappingConfig(configFile("mapping.toml"));
  BrushConfig brush = loadDefaultBrushConfig();
  int64_t t0 = 50 * kSecond;

  bool open(const std::string& name) {
    prepare(name);
    settle_frames = 3;
    test::StudyRigOptions options;
    options.width = kW, options.height = kH;
    options.keep_prefix = "study_";
    options.adjust = [this](StudyRunOptions& run) {
      run.info.protocol_version = protocol.version;
      run.info.display_platform = display->platformName();
      run.info.display_width = kW;
      run.info.display_height = kH;
    };
    now = t0;
    start(protocol, options);
    return !::testing::Test::HasFatalFailure();
  }
};

bool anyContains(const std::vector<std::string>& lines, const std::string& part) {
  for (const std::string& l : lines)
    if (l.find(part) != std::string::npos) return true;
  return false;
}

// Consent by "I agree", the participant code, the introduction: the tutorial begins.
void consentToTutorial(Rig& rig) {
  StudyRunState& state = *rig.state;
  rig.keep("consent");
  EXPECT_TRUE(rig.shown("I agree"));
  EXPECT_TRUE(rig.shown("Waiting for your consent"));
  rig.tap(StudyTargetAction::kAgree);
  ASSERT_EQ(state.stage(), StudyStageKind::kParticipant);
  EXPECT_TRUE(rig.session->penCaptured()) << "the form holds the pen: taps never paint";
  EXPECT_EQ(rig.session->strokesMapped(), 0u);
  rig.keep("participant");
  EXPECT_TRUE(rig.shown("P01"));
  rig.tap(StudyTargetAction::kContinue);
  ASSERT_EQ(state.stage(), StudyStageKind::kIntroduction);
  rig.keep("introduction");
  rig.keys("space");
  ASSERT_EQ(state.stage(), StudyStageKind::kTutorial);
}

// The tutorial: each step waits until the participant does it; its check reads in words.
void tutorialByKeysAndAStroke(Rig& rig) {
  StudyRunState& state = *rig.state;
  rig.keep("tutorial");
  EXPECT_TRUE(rig.shown("Reset the camera"));
  // The step's check in words, English over Chinese; never its expression.
  EXPECT_TRUE(rig.shown("Turn the camera to the starting view (not yet)"));
  EXPECT_TRUE(rig.shown("把相机转到初始视角（还没有）"));
  EXPECT_FALSE(rig.shown("camera_view"));
  rig.frames(3);
  EXPECT_EQ(state.tutorialStep(), 0) << "nothing done, nothing advances";
  rig.keys("r");  // the tutorial starts in Camera mode, where R acts
  EXPECT_EQ(state.tutorialStep(), 1);
  rig.keys("3");
  EXPECT_EQ(state.tutorialStep(), 1) << "Paint mode is not the Canvas mode asked for";
  rig.keys("2");
  EXPECT_EQ(state.tutorialStep(), 2);
  rig.keys("3");
  EXPECT_EQ(state.tutorialStep(), 3);
  rig.keys("b");
  EXPECT_EQ(state.tutorialStep(), 4);
  EXPECT_EQ(rig.session->mode(), Mode::kPaint);
  rig.keep("tutorial_stroke_step");
  // Before the first stroke the painter's hint shows, above the page's foot line.
  const float* hint = rig.screen->paintScreen().ui()->hintRect();
  const StudyPage& page = rig.screen->page();
  EXPECT_GT(hint[3], hint[1]) << "the painter's first-screen hint is shown";
  EXPECT_LE(hint[3], page.foot[1])
      << "the hint's foot " << hint[3] << " is below the foot line's top " << page.foot[1];
  rig.stroke(referencePaintStrokes(kW, kH)[0]);
  rig.frames(2);
  ASSERT_EQ(state.stage(), StudyStageKind::kTask) << state.waitingFor(rig.now);
}

// The task: an empty sky, the picture beside it, the countdown; one stroke, then time is up.
void taskUntilTimeUp(Rig& rig) {
  StudyRunState& state = *rig.state;
  EXPECT_EQ(state.task()->id, "cloud1");
  rig.frames(1);
  rig.keep("task");
  EXPECT_TRUE(rig.shown("Time left 1:00") || rig.shown("Time left 0:5"))
      << "a one-minute countdown";
  EXPECT_GT(rig.screen->page().image[2], rig.screen->page().image[0]) << "the reference picture";
  rig.stroke(referencePaintStrokes(kW, kH)[1]);
  EXPECT_EQ(rig.session->strokesMapped(), 2u);
  rig.frames(1, 61 * kSecond);
  rig.frames(2);
  ASSERT_EQ(state.stage(), StudyStageKind::kDemographics) << state.waitingFor(rig.now);
}

// Demographics on the on-screen keyboard: an age out of range is refused and said so.
void demographicsOnTheKeyboard(Rig& rig) {
  StudyRunState& state = *rig.state;
  rig.tapKey("9");
  rig.tap(StudyTargetAction::kOk);
  EXPECT_EQ(state.fieldIndex(), 0);
  rig.keep("demographics_refused");
  EXPECT_TRUE(rig.shown("whole number from 16 to 99"));
  rig.tap(StudyTargetAction::kBackspace);
  rig.tapKey("3");
  rig.tapKey("4");
  rig.tap(StudyTargetAction::kOk);
  ASSERT_EQ(state.fieldIndex(), 1);
  rig.tapKey("f");
  rig.keep("demographics_text");
  rig.tap(StudyTargetAction::kOk);
  rig.tap(StudyTargetAction::kSkipField);
  ASSERT_EQ(state.stage(), StudyStageKind::kQuestionnaire);
}

// The questionnaire: one tap per item; item 5 skipped; the last is the lag item.
void questionnaireByTaps(Rig& rig) {
  StudyRunState& state = *rig.state;
  const size_t items = rig.protocol.items.size();
  ASSERT_EQ(items, 28u);
  for (size_t i = 0; i < items; ++i) {
    ASSERT_EQ(state.itemIndex(), int(i));
    if (i == 0) rig.keep("questionnaire");
    if (i == items - 1) {
      rig.keep("questionnaire_lag_item");
      std::string lag = rig.protocol.items.back().text;  // shown without the *emphasis* marks
      lag.erase(std::remove(lag.begin(), lag.end(), '*'), lag.end());
      EXPECT_TRUE(rig.shown(lag)) << lag;
      EXPECT_NE(lag.find("wait after each stroke"), std::string::npos) << "the lag item";
    }
    if (i == 4)
      rig.tap(StudyTargetAction::kSkipItem);
    else
      rig.tap(StudyTargetAction::kAnswer, int(i % 5) + 1);
  }
}

// Free text typed on every keyboard page and a physical keyboard, into `free_text`; OK ends
// the session.
void freeTextBeyondAsciiToTheEnd(Rig& rig, std::string* free_text) {
  StudyRunState& state = *rig.state;
  ASSERT_EQ(state.stage(), StudyStageKind::kFreeText);
  // Free text beyond lowercase ASCII: Shift, the symbols page, the protocol's Chinese page
  // (bundled protocol's [keyboard]), then a physical keyboard's text (an input method's UTF-8)
  // and its BackSpace, which deletes one character (all of its bytes).
  rig.tapKey("o");
  rig.tapKey("k");
  rig.tap(StudyTargetAction::kKeyboardPage, kKeyboardUpper);
  rig.keep("free_text_shift");
  rig.tapKey("K");
  rig.tap(StudyTargetAction::kKeyboardPage, kKeyboardSymbols);
  rig.keep("free_text_symbols");
  rig.tapKey("\u20ac");  // €
  rig.tap(StudyTargetAction::kKeyboardPage, kKeyboardProtocol);
  rig.keep("free_text_chinese");
  rig.tapKey("\u4e91");                                                    // 云
  const std::string typed = " \u00dcn\u00efc\u00f6d\u00e9 \u4e91 \u2601";  // " Ünïcödé 云 ☁"
  for (const std::string& text : {std::string(" \u00dcn\u00efc\u00f6d\u00e9 \u4e91 "),
                                  std::string("\u96fe"), std::string("\u2601")}) {
    DisplayEvent key = DisplayEvent::key(0x20);
    key.text = text;
    EXPECT_TRUE(rig.screen->onKey(key, rig.now));
    rig.frames(1);
  }
  EXPECT_TRUE(rig.screen->onKey(DisplayEvent::key(0xff08), rig.now));  // BackSpace: the ☁
  EXPECT_TRUE(rig.screen->onKey(DisplayEvent::key(0xff08), rig.now));  // and the 雾
  DisplayEvent cloud = DisplayEvent::key(0x1002601);
  cloud.text = "\u2601";
  EXPECT_TRUE(rig.screen->onKey(cloud, rig.now));
  // The operator's Ctrl+Alt keys are not typed.
  EXPECT_FALSE(
      rig.screen->onKey(DisplayEvent::key('p', DisplayEvent::kCtrl | DisplayEvent::kAlt), rig.now));
  *free_text = "okK\u20ac\u4e91" + typed;

  rig.keep("free_text");
  EXPECT_TRUE(rig.shown(*free_text + "_")) << "the field shows what was typed";
  rig.tap(StudyTargetAction::kOk);
  ASSERT_TRUE(state.done());
  rig.keep("done");
  rig.frames(200, kSecond / 10);
  EXPECT_EQ(rig.quit, "study complete");
  EXPECT_TRUE(rig.screen->problems().empty()) << rig.screen->problems().front();
}

// The folder: answers as tapped, demographics with `free_text`, session.json.
void checkAnswersAndSession(Rig& rig, const std::string& free_text) {
  const size_t items = rig.protocol.items.size();
  const LikertAnswers answers = loadLikertAnswers(rig.folder + "/questionnaire.csv");
  ASSERT_EQ(answers.participants, std::vector<std::string>{"P01"});
  ASSERT_EQ(answers.items.size(), items);
  for (size_t i = 0; i < items; ++i) {
    if (i == 4)
      EXPECT_FALSE(answers.answers[0][i].has_value());
    else
      EXPECT_EQ(answers.answers[0][i], int(i % 5) + 1) << answers.items[i];
  }
  EXPECT_EQ(
      readText(rig.folder + "/demographics.csv"),
      "participant,age,gender,modelling_experience,feedback\nP01,34,f,NA," + free_text + "\n");
  const std::string json = readText(rig.folder + "/session.json");
  EXPECT_NE(json.find("\"status\": \"completed\""), std::string::npos) << json;
  EXPECT_NE(json.find("cloudbrush synthetic tablet"), std::string::npos) << json;
  EXPECT_NE(json.find("\"stages_completed\": [\"consent\", \"participant\", \"introduction\", "
                      "\"tutorial\", \"task:cloud1\", \"demographics\", \"questionnaire\", "
                      "\"free-text\"]"),
            std::string::npos)
      << json;
}

// The journal's records; the free text survives them; the sync markers.
void checkMarkersRestoreAndSync(Rig& rig, const std::string& free_text) {
  const std::vector<std::string> markers = rig.markers();
  EXPECT_TRUE(anyContains(markers, "study.consent agreed=yes participant=P01"));
  EXPECT_TRUE(anyContains(markers, "study.tutorial-step done step=9"));
  EXPECT_TRUE(anyContains(markers,
                          "study.stage-closing stage=task task=cloud1 position=1 "
                          "why=\"time up\""));
  EXPECT_TRUE(anyContains(markers, "study.saved stage=task task=cloud1"));
  EXPECT_TRUE(anyContains(markers, "study.answer item=Q28 value=3"));
  EXPECT_TRUE(anyContains(markers, "study.end completed"));
  // The free text survives the journal byte for byte: a state restored from the journal's
  // markers (a resumed session) writes the same answer file, and the events export holds it.
  {
    std::vector<StudyRunRecord> records;
    for (const JournalRecord& r : readJournal(rig.folder + "/session.cbj").records)
      if (r.type == JournalRecordType::kMarker && r.text().substr(0, 6) == "study.")
        records.push_back({r.t_ns, std::string(r.text())});
    StudyRunState restored(rig.protocol, 1, rig.t0);
    std::string error;
    ASSERT_TRUE(restored.restore(records, &error)) << error;
    EXPECT_EQ(restored.demographicsCsv(), readText(rig.folder + "/demographics.csv"));
    std::ostringstream events;
    writeEventsCsv(events, {loadSessionTrace(rig.folder + "/session.cbj")});
    EXPECT_NE(events.str().find("value=\"\"" + free_text + "\"\""), std::string::npos)
        << "events.csv holds the answer's bytes";
  }
  // The task's boundaries reach other recorders as sync markers (JOURNAL.md §10).
  const std::vector<std::string> sync = rig.syncMarkers();
  EXPECT_TRUE(anyContains(sync, "kind=task_begin"));
  EXPECT_TRUE(anyContains(sync, "kind=task_end"));
  EXPECT_TRUE(anyContains(sync, "label=stage=task task=cloud1 position=1"));
}

// The task's files read back: the VDB holds the cloud, the EXR and PNG the screen's size.
void checkTaskFiles(Rig& rig) {
  const Volume& volume = rig.session->volume();
  size_t nonzero = 0;
  for (float d : volume.toDense()) nonzero += d != 0.0f;
  ASSERT_GT(nonzero, 0u);
  openvdb::initialize();
  openvdb::io::File vdb(rig.folder + "/tasks/cloud1.vdb");
  vdb.open();
  const auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(vdb.readGrid("density"));
  ASSERT_TRUE(grid);
  EXPECT_EQ(grid->activeVoxelCount(), openvdb::Index64(nonzero));
  vdb.close();
  Imf::InputFile exr((rig.folder + "/tasks/cloud1.exr").c_str());
  const Imath::Box2i window = exr.header().dataWindow();
  EXPECT_EQ(window.max.x - window.min.x + 1, kW);
  EXPECT_EQ(window.max.y - window.min.y + 1, kH);
  EXPECT_TRUE(exr.header().channels().findChannel("R"));
  const ImageRgba8 png = readPng(rig.folder + "/tasks/cloud1.png");
  if (const char* keep = std::getenv("CB_KEEP_FRAMES"))
    writePng(std::string(keep) + "/study_task_export.png", png);
  EXPECT_EQ(png.width, kW);
  EXPECT_TRUE(std::filesystem::exists(rig.folder + "/tasks/cloud1.cbvol"));
}

TEST(StudyRunScreen, ConsentTutorialTaskAndQuestionnaireByPen) {
  Rig rig;
  if (!rig.open("cb_study_run_")) return;
  ASSERT_NO_FATAL_FAILURE(consentToTutorial(rig));
  ASSERT_NO_FATAL_FAILURE(tutorialByKeysAndAStroke(rig));
  ASSERT_NO_FATAL_FAILURE(taskUntilTimeUp(rig));
  ASSERT_NO_FATAL_FAILURE(demographicsOnTheKeyboard(rig));
  ASSERT_NO_FATAL_FAILURE(questionnaireByTaps(rig));
  std::string free_text;
  ASSERT_NO_FATAL_FAILURE(freeTextBeyondAsciiToTheEnd(rig, &free_text));
  ASSERT_NO_FATAL_FAILURE(checkAnswersAndSession(rig, free_text));
  ASSERT_NO_FATAL_FAILURE(checkMarkersRestoreAndSync(rig, free_text));
  ASSERT_NO_FATAL_FAILURE(checkTaskFiles(rig));

  // The journal replays (study markers are skipped) to the session's cloud.
  const SessionReplay replay =
      replaySession(readJournal(rig.folder + "/session.cbj"), rig.brush, rig.mapping);
  ASSERT_TRUE(replay.session);
  EXPECT_EQ(volumeChecksum(replay.session->volume()), volumeChecksum(rig.session->volume()));
  rig.screen.reset();
  std::filesystem::remove_all(rig.dir);
}

TEST(StudyRunScreen, OperatorPausesSkipsAndAbortsWithAReason) {
  Rig rig;
  if (!rig.open("cb_study_operator_")) return;
  StudyRunState& state = *rig.state;
  rig.frames(1);
  rig.tap(StudyTargetAction::kAgree);
  // Pause: a reason by digit key; the participant's buttons wait; resume.
  rig.keys("ctrl+alt+p");
  ASSERT_TRUE(state.choosing());
  rig.keep("operator_chooser");
  EXPECT_TRUE(rig.shown("Operator: why pause?"));
  rig.keys("2");
  ASSERT_TRUE(state.paused());
  rig.keep("paused");
  EXPECT_TRUE(rig.shown("Paused by the operator (participant needs a break)"));
  rig.keys("space");
  EXPECT_EQ(state.stage(), StudyStageKind::kParticipant) << "nothing moves while paused";
  rig.keys("ctrl+alt+p");
  EXPECT_FALSE(state.paused());
  rig.keys("space");
  ASSERT_EQ(state.stage(), StudyStageKind::kIntroduction);
  // Skip the introduction with a reason tapped by the pen; Esc cancels a chooser.
  rig.keys("ctrl+alt+a");
  rig.keys("esc");
  EXPECT_FALSE(state.choosing());
  EXPECT_FALSE(state.done());
  rig.keys("ctrl+alt+s");
  rig.tap(StudyTargetAction::kReason, 0);
  ASSERT_EQ(state.stage(), StudyStageKind::kTutorial);
  // Skip the steps (step 7, "Paint mode", holds already and passes by itself).
  for (int i = 0; i < 10 && state.stage() == StudyStageKind::kTutorial; ++i)
    rig.keys("ctrl+alt+s,4");
  rig.frames(2);
  ASSERT_EQ(state.stage(), StudyStageKind::kTask);
  // In the task, the clock stops while paused.
  rig.frames(1, 10 * kSecond);
  const double left = state.secondsLeft(rig.now);
  rig.keys("ctrl+alt+p,1");
  rig.frames(3, 100 * kSecond);
  EXPECT_EQ(state.stage(), StudyStageKind::kTask);
  EXPECT_NEAR(state.secondsLeft(rig.now), left, 0.5);
  rig.keys("ctrl+alt+p");
  // Abort: the task's files are saved, then the session ends as aborted.
  rig.keys("ctrl+alt+a");
  rig.keep("operator_abort");
  rig.tap(StudyTargetAction::kReason, 2);
  rig.frames(2);
  ASSERT_TRUE(state.done());
  EXPECT_TRUE(state.aborted());
  rig.keep("aborted");
  rig.frames(50, kSecond / 10);
  EXPECT_EQ(rig.quit, "study aborted");
  const std::string json = readText(rig.folder + "/session.json");
  EXPECT_NE(json.find("\"status\": \"aborted\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"abort_reason\": \"technical problem\""), std::string::npos) << json;
  EXPECT_TRUE(std::filesystem::exists(rig.folder + "/tasks/cloud1.vdb"));
  const std::vector<std::string> markers = rig.markers();
  EXPECT_TRUE(anyContains(markers,
                          "study.operator action=pause reason=\"participant needs a "
                          "break\" stage=participant"));
  EXPECT_TRUE(anyContains(markers, "study.operator action=resume stage=participant"));
  EXPECT_TRUE(anyContains(markers, "study.operator-cancel action=abort stage=introduction"));
  EXPECT_TRUE(anyContains(markers,
                          "study.operator action=skip reason=\"participant finished "
                          "early\" stage=introduction"));
  EXPECT_TRUE(anyContains(markers, "study.tutorial-step skipped step=2"));
  EXPECT_TRUE(anyContains(markers,
                          "study.operator action=abort reason=\"technical problem\" "
                          "stage=task task=cloud1"));
  EXPECT_TRUE(anyContains(markers, "study.end aborted"));
  const LikertAnswers answers = loadLikertAnswers(rig.folder + "/questionnaire.csv");
  for (const auto& a : answers.answers.at(0)) EXPECT_FALSE(a.has_value());
  rig.screen.reset();
  std::filesystem::remove_all(rig.dir);
}

// Restarting on the session (`study run --resume`, as command_study.cpp does it): the journal
// replayed into a new session, the runner's state restored from its markers, a new screen. The
// tutorial step under way keeps its counters (two of its four strokes, the circle overlay
// turned on) and the painter's menu is open as it was; two more strokes then finish the step.
TEST(StudyRunScreen, AResumedTutorialStepKeepsItsCountersAndTheMenu) {
  Rig rig;
  StudyProtocol protocol = loadStudyProtocol(defaultStudyProtocolPath());
  rig.protocol.tutorial = {protocol.tutorial[21], protocol.tutorial[23]};  // Paint mode; 4 strokes
  ASSERT_EQ(rig.protocol.tutorial[1].expect.at(0).text(), "strokes_in_step >= 4");
  if (!rig.open("cb_study_resume_")) return;
  rig.frames(1);
  rig.tap(StudyTargetAction::kAgree);
  rig.tap(StudyTargetAction::kContinue);
  rig.keys("space");
  ASSERT_EQ(rig.state->stage(), StudyStageKind::kTutorial);
  rig.keys("3");
  ASSERT_EQ(rig.state->tutorialStep(), 1);
  rig.stroke(referencePaintStrokes(kW, kH)[0]);
  rig.stroke(referencePaintStrokes(kW, kH)[1]);
  rig.keys("c,m");
  ASSERT_EQ(rig.state->tutorialStep(), 1);
  TutorialState before = rig.screen->tutorialState();
  EXPECT_EQ(before.numbers["strokes_in_step"], 2);
  EXPECT_EQ(before.numbers["circles_shown"], 1);
  EXPECT_EQ(before.numbers["menu_open"], 1);
  rig.keep("before_restart");

  // The restart, 30 s later.
  ASSERT_TRUE(rig.journal.sync());
  rig.screen.reset();
  const JournalReadResult read = readJournal(rig.folder + "/session.cbj");
  ASSERT_TRUE(read.error.empty()) << read.error;
  std::vector<StudyRunRecord> markers;
  int64_t last_ns = 0;
  for (const JournalRecord& r : read.records) {
    // The test's clock is the pen's and the runner's (the calibration's records carry the
    // machine's monotonic time: the rig gives the painter no clock).
    if (r.type == JournalRecordType::kPenSample) last_ns = std::max(last_ns, r.t_ns);
    if (r.type == JournalRecordType::kMarker && r.text().rfind("study.", 0) == 0) {
      markers.push_back({r.t_ns, std::string(r.text())});
      last_ns = std::max(last_ns, r.t_ns);
    }
  }
  EXPECT_TRUE(anyContains(
      [&] {
        std::vector<std::string> texts;
        for (const StudyRunRecord& m : markers) texts.push_back(m.text);
        return texts;
      }(),
      "study.step-progress step=2 strokes=2 brush_changes=0 erasures=0 undos=0 saves=0 "
      "circles_shown=1"));
  SessionReplay replay = replaySession(read, rig.brush, rig.mapping);
  ASSERT_TRUE(replay.complete()) << replay.problems.size();
  EXPECT_TRUE(replay.session->menuOpen()) << "the menu is journalled (menu=open)";
  StudyRunState state(rig.protocol, 1, markers.front().t_ns);
  std::string error;
  ASSERT_TRUE(state.restore(markers, &error)) << error;
  const int64_t restart = last_ns + 30 * kSecond;
  state.resumedAfter(last_ns, restart);
  StudyRunOptions options;
  options.folder = rig.folder;
  options.end_seconds = 1.0;
  options.info.participant_number = 1;
  options.paint.config_dir = rig.dir + "/config";
  options.paint.state_dir = rig.dir + "/state";
  options.resumed = true;
  options.start_ns = restart;
  options.last_mapped = replay.last_mapped;
  rig.screen = std::make_unique<StudyRunScreen>(*rig.display, rig.renderer, *replay.session,
                                                rig.pen_source.get(), nullptr, state, options);
  StudyRunScreen& resumed = *rig.screen;
  rig.now = restart;
  // The resumed screen goes before the session and state it uses.
  struct Release {
    test::StudyScreenRig& rig;
    ~Release() { rig.screen.reset(); }
  } release{rig};
  rig.frames(1);
  ASSERT_EQ(state.stage(), StudyStageKind::kTutorial);
  ASSERT_EQ(state.tutorialStep(), 1);
  TutorialState after = resumed.tutorialState();
  EXPECT_EQ(after.numbers["strokes_in_step"], 2) << "the step's strokes carry on";
  EXPECT_EQ(after.numbers["circles_shown"], 1);
  EXPECT_EQ(after.numbers["menu_open"], 1);
  EXPECT_TRUE(resumed.paintScreen().menuOpen());
  EXPECT_TRUE(resumed.paintScreen().circlesShown());
  rig.keep("resumed_tutorial_menu");
  rig.keys("m");
  EXPECT_FALSE(resumed.paintScreen().menuOpen());
  rig.keep("resumed_tutorial");
  EXPECT_TRUE(rig.shown("Paint 4 strokes (2 of 4 so far)"));
  EXPECT_TRUE(rig.shown("画 4 笔（目前 2 / 4）"));
  EXPECT_LT(state.stageSeconds(rig.now), 60.0) << "the 30 s down do not count";
  rig.stroke(referencePaintStrokes(kW, kH)[0]);
  EXPECT_EQ(state.stage(), StudyStageKind::kTutorial) << "three of four";
  rig.stroke(referencePaintStrokes(kW, kH)[1]);
  rig.frames(2);
  EXPECT_NE(state.stage(), StudyStageKind::kTutorial) << "the fourth stroke ends the step";
  std::filesystem::remove_all(rig.dir);
}

}  // namespace
}  // namespace cb
