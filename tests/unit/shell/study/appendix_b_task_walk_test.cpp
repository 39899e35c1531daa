// One timed task of Appendix B ("Cloud painting ... Save the data in the end") walked at
// 1920x1080 as a participant meets it with no operator beside them: the real study runner
// (EGL surfaceless, llvmpipe) with the bundled protocol (its tutorial and free drawing left to
// their own walks; the four tasks of ten minutes, Williams order), the product's brush and
// mapping. Taps land at the centre of the runner's own targets; the strokes come from a recorded
// pen journal played by the replay backend (drivers/replay). At each step the test reads what
// the screen says and the runner's state:
// - consent, code and introduction each say what they wait for;
// - the task's panel: its title, its picture, what to do and that the cloud is saved for the
//   participant, "I'm done", the countdown (10:00, then red in the last minute), the foot line;
// - three strokes paint (the status line names the recorded pen);
// - the save as Appendix B asks, with the pen through the painter's menu: the toast says which
//   cloud was saved ("task 1, save 1"; no folder), the file lies in the session folder's saved/,
//   the toast's box clear of the task's panel;
// - time up while the pen is down: the panel says time is up and to lift the pen (no "I'm
//   done" any more), the countdown shows 0:00 in red; lifted, the stroke is not lost, the stage
//   closes by itself, the task's files are written, trials.csv says `time-up`, and the next task's
//   page follows at 10:00, saying "Task 1 saved." for five seconds; task titles on one line.
//
// CB_KEEP_FRAMES=DIR writes each step as appendix_b_NN_<step>.png for looking.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "app/brush/synthetic_strokes.h"
#include "app/core/config_paths.h"
#include "app/render/image_io.h"
#include "app/session/paint_session.h"
#include "app/session/synthetic_session.h"
#include "app/shell/painter/paint_screen.h"
#include "app/shell/study/study_run_screen.h"
#include "app/study/session_trace.h"
#include "app/study/trial_table.h"
#include "drivers/replay/replay_pen_source.h"

#include "tests/support/short_study.h"
#include "tests/support/test_display.h"
#include "tests/unit/shell/study/study_screen_rig.h"

namespace cb {
namespace {

constexpr int kW = 1920, kH = 1080;
constexpr int64_t kSecond = 1'000'000'000;
constexpr int64_t kFrame = 16'666'667;

StudyProtocol walkProtocol() {
  StudyProtocol p = loadStudyProtocol(defaultStudyProtocolPath());
  p.tutorial.clear();
  p.free_drawing = StudyStage{};
  return p;
}

SyntheticStroke strokeAcross(glm::vec2 a, glm::vec2 b) {
  SyntheticStroke s;
  s.control_points = {a, glm::mix(a, b, 0.33f) + glm::vec2(0, -40),
                      glm::mix(a, b, 0.66f) + glm::vec2(0, 40), b};
  return s;
}

// The participant's strokes on the canvas (left of the panel): a duck's body, head and beak.
const std::vector<SyntheticStroke> kStrokes = {
    strokeAcross({0.15f * kW, 0.6f * kH}, {0.55f * kW, 0.62f * kH}),
    strokeAcross({0.45f * kW, 0.35f * kH}, {0.55f * kW, 0.42f * kH}),
    strokeAcross({0.55f * kW, 0.4f * kH}, {0.65f * kW, 0.41f * kH})};

// The runner on a test display (study_screen_rig.h) with the recorded pen.
class Walk : public test::StudyScreenRig {
 public:
  std::vector<size_t> stroke_samples;

  // The recorded pen: a Device record and kStrokes, 200 samples a second.
  void recordPen(const std::string& path) {
    JournalWriter writer;
    ASSERT_TRUE(writer.open(path));
    const PenDeviceInfo device = syntheticTablet(kW, kH);
    PaintSession recorder({kW, kH}, loadDefaultBrushConfig(),
                          loadMappingConfig(configFile("mapping.toml")));
    recorder.recordTo(&writer, 0);
    recorder.setDevice(device, 0);
    int64_t t = kSecond;
    for (const SyntheticStroke& s : kStrokes) {
      const std::vector<PenSample> samples = syntheticPenSamples(s, device, kW, kH, 200.0, t);
      for (const PenSample& sample : samples) writer.appendPenSample(sample);
      stroke_samples.push_back(samples.size());
      t = samples.back().t_ns + 200'000'000;
    }
  }

  void open() {
    prepare("cb_appendix_b_");
    ASSERT_NO_FATAL_FAILURE(recordPen(dir + "/pen.cbj"));
    test::StudyRigOptions options;
    options.pen_journal = dir + "/pen.cbj";
    options.keep_prefix = "appendix_b_";
    options.numbered = true;
    options.adjust = [](StudyRunOptions& run) { run.end_seconds = 8.0; };
    ASSERT_NO_FATAL_FAILURE(start(walkProtocol(), options));
  }

  // The label that is exactly `text` is drawn on one line (measured with the runner's font,
  // whose line height is at most 1.5 times the size).
  void expectOneLine(const std::string& text) const {
    const UiLabel* l = nullptr;
    for (const UiLabel& c : screen->page().labels)
      if (c.text == text) l = &c;
    ASSERT_TRUE(l) << "no label '" << text << "': " << words();
    float r[4];
    screen->paintScreen().ui()->labelRect(*l, r);
    EXPECT_LT(r[3] - r[1], 1.5f * l->size_px) << "'" << text << "' wraps";
    EXPECT_LE(r[2], float(kW)) << "'" << text << "' runs off the screen";
  }
};

// Consent, the code, the introduction: each page says what it waits for.
void consentCodeIntroduction(Walk& w) {
  w.keep("consent");
  EXPECT_TRUE(w.shown("Waiting for your consent")) << w.words();
  EXPECT_TRUE(w.shown("You are invited to take part")) << w.words();
  ASSERT_NO_FATAL_FAILURE(w.tap(StudyTargetAction::kAgree));
  w.keep("participant_code");
  EXPECT_TRUE(w.shown("P01")) << w.words();
  ASSERT_NO_FATAL_FAILURE(w.tap(StudyTargetAction::kContinue));
  w.keep("introduction");
  EXPECT_TRUE(w.shown("Read the introduction")) << w.words();
  ASSERT_NO_FATAL_FAILURE(w.tap(StudyTargetAction::kContinue));
  ASSERT_EQ(w.state->stage(), StudyStageKind::kTask) << w.state->waitingFor(w.now);
  w.frames(3);
}

// The task's page before the first stroke.
void checkTaskStart(Walk& w, const StudyTask* task) {
  ASSERT_TRUE(task);
  w.keep("task_start");
  EXPECT_TRUE(w.shown("Task 1 of 4")) << w.words();
  ASSERT_NO_FATAL_FAILURE(w.expectOneLine(task->title));
  EXPECT_FALSE(w.shown("saved.")) << "no task ended before the first: " << w.words();
  EXPECT_TRUE(w.shown("Paint a cloud like the picture.")) << w.words();
  EXPECT_TRUE(w.shown("saved for you when you tap \"I'm done\" or when the time is up"))
      << w.words();
  EXPECT_TRUE(w.shown("Time left 10:00")) << w.words();
  EXPECT_TRUE(w.shown("剩余时间 10:00")) << "the countdown's Chinese: " << w.words();
  EXPECT_TRUE(w.shown("Paint with the pen. Time left 10:00. Tap \"I'm done\" when finished."))
      << w.words();
  EXPECT_TRUE(w.screen->page().find(StudyTargetAction::kDone));
  EXPECT_GT(w.screen->page().image[2] - w.screen->page().image[0], 0.2f * kW)
      << "the picture is shown in the panel";
  EXPECT_TRUE(w.screen->paintScreen().ui()->statusFits()) << "the status line is not cut";
  // The painter's first-screen hint, shown until the first stroke, sits above the foot line.
  const float* hint = w.screen->paintScreen().ui()->hintRect();
  const float* foot = w.screen->page().foot;
  EXPECT_GT(hint[3], hint[1]) << "the painter's first-screen hint is shown";
  EXPECT_LE(hint[3], foot[1]) << "the hint (" << hint[0] << "," << hint[1] << ")-(" << hint[2]
                              << "," << hint[3] << ") runs into the foot line from " << foot[1];
}

// Three strokes with the recorded pen, a minute apart on the task's clock.
void threeStrokes(Walk& w) {
  for (size_t s = 0; s < kStrokes.size(); ++s) {
    ASSERT_NO_FATAL_FAILURE(w.recordedStroke(w.stroke_samples[s]));
    w.frames(3);
    w.frames(1, 60 * kSecond);
    EXPECT_EQ(w.session->strokesMapped(), s + 1);
  }
  w.frames(2);
  w.keep("three_strokes");
  const double left = w.state->secondsLeft(w.now);
  EXPECT_LT(left, 7 * 60) << "three minutes and the strokes' seconds gone";
  EXPECT_TRUE(w.shown("Time left " + countdownText(left))) << w.words();
}

// "Save the data in the end" (Appendix B), with the pen: the menu button, then Save.
void saveByTheMenu(Walk& w) {
  const float* menu = w.screen->paintScreen().ui()->menuButtonRect();
  ASSERT_GT(menu[2], menu[0]);
  w.tapAt(0.5f * (menu[0] + menu[2]), 0.5f * (menu[1] + menu[3]));
  w.frames(2);  // ImGui shows a new window on its second frame
  ASSERT_TRUE(w.screen->paintScreen().menuOpen());
  w.keep("menu_open");
  float save[4];
  ASSERT_TRUE(w.screen->paintScreen().ui()->targetRect(Command::kSave, save));
  w.tapAt(0.5f * (save[0] + save[2]), 0.5f * (save[1] + save[3]));
  w.frames(2);
  w.keep("saved");
  const std::string saved = w.screen->paintScreen().lastSaved();
  ASSERT_NE(saved, "");
  EXPECT_EQ(std::filesystem::path(saved).parent_path(), std::filesystem::path(w.folder + "/saved"));
  // The participant reads which cloud was saved, not where: the folder is the log's.
  const std::string said = w.screen->paintScreen().toast();
  EXPECT_NE(said.find("Your cloud is saved (task 1, save 1)."), std::string::npos) << said;
  EXPECT_NE(said.find("您的云已保存"), std::string::npos) << said;
  EXPECT_EQ(said.find(w.folder), std::string::npos) << "no folder in the toast: " << said;
  EXPECT_EQ(said.find('/' + std::filesystem::path(saved).filename().string()), std::string::npos)
      << said;
  const float* toast = w.screen->paintScreen().ui()->toastRect();
  EXPECT_GE(toast[0], 0.0f) << "the save's answer on the screen";
  EXPECT_LE(toast[2], kStudyPanelLeft * kW) << "the save's answer clear of the task's panel";
  EXPECT_EQ(w.session->strokesMapped(), kStrokes.size()) << "the menu's taps never paint";
  if (w.screen->paintScreen().menuOpen()) {
    w.tapAt(0.5f * (menu[0] + menu[2]), 0.5f * (menu[1] + menu[3]));  // closed again
    w.frames(2);
  }
}

// The last minute: the countdown turns red.
void lastMinuteRed(Walk& w) {
  w.frames(1, int64_t(w.state->secondsLeft(w.now) - 45) * kSecond);
  w.frames(2);
  w.keep("last_minute");
  const UiLabel* countdown = w.label("Time left 0:4");
  ASSERT_TRUE(countdown) << w.words();
  EXPECT_EQ(countdown->rgba, 0xff8060ffu) << "red in the last minute";
  const UiLabel* countdown_zh = w.label("剩余时间 0:4");
  ASSERT_TRUE(countdown_zh) << w.words();
  EXPECT_EQ(countdown_zh->rgba, 0xff8060ffu) << "its Chinese red too";
}

// Time up with the pen down in a stroke: the page asks to lift the pen; lifted, the stage
// closes by itself and the stroke is kept (`closing`: what the closing page said).
void timeUpWithThePenDown(Walk& w, std::string* closing) {
  const SyntheticStroke last_stroke = strokeAcross({0.2f * kW, 0.3f * kH}, {0.3f * kW, 0.32f * kH});
  std::vector<PenSample> down, up;
  bool was_down = false;  // hover in and the tip's samples, then the lift and what follows
  for (const PenSample& s : syntheticPenSamples(last_stroke, w.tablet, kW, kH, 200.0, w.now)) {
    (up.empty() && (s.tipDown() || !was_down) ? down : up).push_back(s);
    was_down = was_down || s.tipDown();
  }
  w.frames(0, kFrame, down);
  w.frames(1, int64_t(w.state->secondsLeft(w.now) + 1) * kSecond);
  w.frames(2);
  w.keep("time_up_pen_down");
  EXPECT_TRUE(w.state->closing());
  *closing = w.state->waitingFor(w.now);
  EXPECT_TRUE(w.shown("lift the pen")) << w.words();
  EXPECT_TRUE(w.shown("Time is up. Lift the pen: your cloud is being saved.")) << w.words();
  EXPECT_TRUE(w.shown("时间到了")) << w.words();
  EXPECT_FALSE(w.screen->page().find(StudyTargetAction::kDone)) << "no \"I'm done\" after time up";
  EXPECT_TRUE(w.shown("Time left 0:00")) << w.words();
  for (PenSample& s : up) s.t_ns = w.now;
  w.frames(0, kFrame, up);
  w.frames(30);
}

// The next task's panel says the last one was saved, for a few seconds; the task's trial
// ended at time up with every stroke, its files written.
void checkNextTask(Walk& w, const StudyTask* task, const std::string& closing) {
  w.keep("next_task");
  // The next task's panel says the last one was saved, for a few seconds.
  EXPECT_TRUE(w.shown("Task 1 saved. 任务 1 已保存。")) << w.words();
  EXPECT_TRUE(w.shown("Task 2 of 4")) << w.words();
  ASSERT_NO_FATAL_FAILURE(w.expectOneLine(w.state->task()->title));
  const std::vector<TrialRow> trials = trialsOfSession(loadSessionTrace(w.folder + "/session.cbj"));
  ASSERT_GE(trials.size(), 1u);
  EXPECT_EQ(trials[0].end_reason, "time-up") << closing;
  EXPECT_EQ(trials[0].strokes, int(kStrokes.size()) + 1) << "the stroke open at time up is kept";
  for (const char* ext : {".vdb", ".cbvol", ".exr", ".png"})
    EXPECT_TRUE(std::filesystem::exists(w.folder + "/tasks/" + task->id + ext)) << ext;
  ASSERT_EQ(w.state->stage(), StudyStageKind::kTask) << w.state->waitingFor(w.now);
  EXPECT_TRUE(w.shown("Time left 10:00") || w.shown("Time left 9:5")) << w.words();
  EXPECT_EQ(w.quit, "") << "the session goes on";
  w.frames(1, 6 * kSecond);  // the notice's five seconds are over
  w.frames(1);
  w.keep("next_task_later");
  EXPECT_FALSE(w.shown("Task 1 saved.")) << w.words();
}

TEST(AppendixB, ATimedTaskAsAParticipantMeetsIt) {
  Walk w;
  ASSERT_NO_FATAL_FAILURE(w.open());
  w.frames(2);
  ASSERT_NO_FATAL_FAILURE(consentCodeIntroduction(w));
  const StudyTask* task = w.state->task();
  ASSERT_NO_FATAL_FAILURE(checkTaskStart(w, task));
  ASSERT_NO_FATAL_FAILURE(threeStrokes(w));
  ASSERT_NO_FATAL_FAILURE(saveByTheMenu(w));
  ASSERT_NO_FATAL_FAILURE(lastMinuteRed(w));
  std::string closing;
  ASSERT_NO_FATAL_FAILURE(timeUpWithThePenDown(w, &closing));
  ASSERT_NO_FATAL_FAILURE(checkNextTask(w, task, closing));
  std::printf("closing page said: %s\n", closing.c_str());
}

}  // namespace
}  // namespace cb
