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

namespace cb {
namespace {

constexpr int kW = 640, kH = 360;
constexpr int64_t kSecond = 1'000'000'000;

using cb::test::readText;

// One raw sample of the synthetic tablet at screen pixel (x, y).
PenSample sampleAt(const PenDeviceInfo& tablet, float x, float y, int64_t t_ns, float pressure,
                   bool tip, bool proximity) {
  PenSample s;
  s.t_ns = t_ns;
  s.x_mm = double(x) * double(tablet.x_max) / tablet.x_res / kW;
  s.y_mm = double(y) * double(tablet.y_max) / tablet.y_res / kH;
  s.x_raw = int32_t(std::lround(s.x_mm * tablet.x_res));
  s.y_raw = int32_t(std::lround(s.y_mm * tablet.y_res));
  s.pressure_raw = int32_t(std::lround(pressure * float(tablet.pressure_max)));
  s.pressure = float(s.pressure_raw) / float(tablet.pressure_max);
  s.distance_raw = tip ? 0 : 10;
  s.distance = float(s.distance_raw) / float(tablet.distance_max);
  s.buttons = tip ? kPenTip : 0u;
  s.tool = proximity ? PenTool::kPen : PenTool::kNone;
  s.tool_id = proximity ? 0x802u : 0u;
  s.in_proximity = proximity;
  return s;
}

// Drives the screen as FrameLoop does, with the test's clock.
class Driver {
 public:
  Driver(Display& display, StudyRunScreen& screen, const PenDeviceInfo& tablet, int64_t t0)
      : display_(display), screen_(screen), tablet_(tablet), now_(t0) {}

  void frames(int n, int64_t step_ns = 16'666'667) {
    for (int i = 0; i < n && quit_.empty(); ++i) {
      now_ += step_ns;
      FrameContext frame{display_, kW, kH, frame_, now_, double(step_ns) / 1e9};
      screen_.onPenSamples({});
      quit_ = screen_.update(frame);
      if (!quit_.empty()) return;
      std::string error;
      ASSERT_TRUE(screen_.draw(frame, &error)) << error;
      if (!keep_.empty()) {
        if (const char* dir = std::getenv("CB_KEEP_FRAMES"))
          writePng(std::string(dir) + "/study_" + keep_ + ".png",
                   readFramebufferRgba8(display_.framebuffer(), kW, kH));
        keep_.clear();
      }
      ASSERT_TRUE(display_.present(&error)) << error;
      ++frame_;
    }
  }
  void keep(const std::string& name) {
    keep_ = name;
    frames(1);
  }
  void keys(const char* list) {
    std::vector<DisplayEvent> events;
    std::string error;
    ASSERT_TRUE(parseKeyList(list, &events, &error)) << error;
    for (const DisplayEvent& e : events) {
      const std::optional<Command> command = commandFor(e);
      ASSERT_TRUE(command) << list;
      screen_.onCommand(*command, now_);
      frames(1);
    }
    frames(1);
  }
  void pen(const std::vector<PenSample>& samples) {
    for (size_t i = 0; i < samples.size(); i += 3) {
      std::vector<PenSample> batch(samples.begin() + long(i),
                                   samples.begin() + long(std::min(samples.size(), i + 3)));
      screen_.onPenSamples(batch);
      frames(1);
    }
    frames(3);
  }
  // A pen tap in the middle of a target of the page last drawn.
  void tap(StudyTargetAction action, int value = -1) {
    const StudyTarget* t = screen_.page().find(action, value);
    ASSERT_TRUE(t) << "no target " << int(action) << " value " << value << " on the page";
    tapAt(0.5f * (t->x0 + t->x1), 0.5f * (t->y0 + t->y1));
  }
  void tapKey(const std::string& key) {
    for (const StudyTarget& t : screen_.page().targets)
      if (t.action == StudyTargetAction::kKey && t.text == key)
        return tapAt(0.5f * (t.x0 + t.x1), 0.5f * (t.y0 + t.y1));
    FAIL() << "no key " << key;
  }
  void tapAt(float x, float y) {
    std::vector<PenSample> s;
    int64_t t = now_;
    const int64_t dt = 5'000'000;
    for (int i = 0; i < 3; ++i) s.push_back(sampleAt(tablet_, x, y, t += dt, 0.0f, false, true));
    for (int i = 0; i < 4; ++i) s.push_back(sampleAt(tablet_, x, y, t += dt, 0.6f, true, true));
    for (int i = 0; i < 2; ++i) s.push_back(sampleAt(tablet_, x, y, t += dt, 0.0f, false, true));
    s.push_back(sampleAt(tablet_, x, y, t += dt, 0.0f, false, false));
    pen(s);
  }
  void stroke(const SyntheticStroke& stroke) {
    pen(syntheticPenSamples(stroke, tablet_, kW, kH, 200.0, now_));
  }
  bool labelShown(const std::string& part) const {
    for (const UiLabel& l : screen_.page().labels)
      if (l.text.find(part) != std::string::npos) return true;
    return false;
  }
  const std::string& quit() const { return quit_; }
  int64_t now() const { return now_; }

 private:
  Display& display_;
  StudyRunScreen& screen_;
  PenDeviceInfo tablet_;
  int64_t now_;
  long frame_ = 0;
  std::string keep_, quit_;
};

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

struct Rig {
  std::string dir, folder;
  std::unique_ptr<Display> display;
  VolumeRenderer renderer;
  MappingConfig mapping = loadMappingConfig(configFile("mapping.toml"));
  BrushConfig brush = loadDefaultBrushConfig();
  std::unique_ptr<PaintSession> session;
  JournalWriter journal;
  PenDeviceInfo tablet = syntheticTablet(kW, kH);
  std::unique_ptr<ReplayPenSource> pen;
  StudyProtocol protocol = shortThesisProtocol();
  std::unique_ptr<StudyRunState> state;
  std::unique_ptr<StudyRunScreen> screen;
  int64_t t0 = 50 * kSecond;

  bool open(const std::string& name) {
    dir = (std::filesystem::temp_directory_path() / (name + std::to_string(::getpid()))).string();
    std::filesystem::remove_all(dir);
    folder = dir + "/data/P01-test";
    std::filesystem::create_directories(folder);
    std::filesystem::create_directories(dir + "/state");
    std::string error;
    display = test::openTestDisplay(kW, kH, &error);
    EXPECT_TRUE(display) << error;
    if (!display) return false;
    EXPECT_TRUE(renderer.init(&error)) << error;
    session = std::make_unique<PaintSession>(PaintSessionSettings{kW, kH}, brush, mapping);
    session->setQuietMapping(true);
    EXPECT_TRUE(journal.open(folder + "/session.cbj"));
    session->recordTo(&journal, t0);
    // The pen: the synthetic tablet, connected (the test hands its samples to the screen).
    std::vector<JournalRecord> records(2);
    records[0].type = JournalRecordType::kDevice;
    records[0].payload = encodeDeviceInfo(tablet);
    records[1].type = JournalRecordType::kPenSample;
    records[1].payload = encodePenSample(sampleAt(tablet, 1, 1, 0, 0, false, false));
    ReplayOptions replay;
    replay.realtime = false;
    pen = std::make_unique<ReplayPenSource>(records, replay);
    state = std::make_unique<StudyRunState>(protocol, 1, t0);
    StudyRunOptions options;
    options.folder = folder;
    options.end_seconds = 1.0;
    options.info.protocol_name = protocol.name;
    options.info.protocol_version = protocol.version;
    options.info.participant_id = state->participantId();
    options.info.participant_number = 1;
    options.info.anchor_monotonic_ns = t0;
    options.info.display_platform = display->platformName();
    options.info.display_width = kW;
    options.info.display_height = kH;
    options.paint.config_dir = dir + "/config";
    options.paint.state_dir = dir + "/state";
    screen = std::make_unique<StudyRunScreen>(*display, renderer, *session, pen.get(), &journal,
                                              *state, options);
    return true;
  }
  std::vector<std::string> markers() {
    journal.sync();
    std::vector<std::string> out;
    for (const JournalRecord& r : readJournal(folder + "/session.cbj").records)
      if (r.type == JournalRecordType::kMarker) out.emplace_back(r.text());
    return out;
  }
  std::vector<std::string> syncMarkers() {
    journal.sync();
    std::vector<std::string> out;
    for (const JournalRecord& r : readJournal(folder + "/session.cbj").records)
      if (r.type == JournalRecordType::kSync) out.emplace_back(r.text());
    return out;
  }
};

bool anyContains(const std::vector<std::string>& lines, const std::string& part) {
  for (const std::string& l : lines)
    if (l.find(part) != std::string::npos) return true;
  return false;
}

TEST(StudyRunScreen, ConsentTutorialTaskAndQuestionnaireByPen) {
  Rig rig;
  if (!rig.open("cb_study_run_")) return;
  Driver d(*rig.display, *rig.screen, rig.tablet, rig.t0);
  StudyRunState& state = *rig.state;

  d.keep("consent");
  EXPECT_TRUE(d.labelShown("I agree"));
  EXPECT_TRUE(d.labelShown("Waiting for your consent"));
  d.tap(StudyTargetAction::kAgree);
  ASSERT_EQ(state.stage(), StudyStageKind::kParticipant);
  EXPECT_TRUE(rig.session->penCaptured()) << "the form holds the pen: taps never paint";
  EXPECT_EQ(rig.session->strokesMapped(), 0u);
  d.keep("participant");
  EXPECT_TRUE(d.labelShown("P01"));
  d.tap(StudyTargetAction::kContinue);
  ASSERT_EQ(state.stage(), StudyStageKind::kIntroduction);
  d.keep("introduction");
  d.keys("space");
  ASSERT_EQ(state.stage(), StudyStageKind::kTutorial);

  // The tutorial: each step waits until the participant does it.
  d.keep("tutorial");
  EXPECT_TRUE(d.labelShown("Reset the camera"));
  EXPECT_TRUE(d.labelShown("camera_view == reset (now none yet, not yet)"));
  d.frames(3);
  EXPECT_EQ(state.tutorialStep(), 0) << "nothing done, nothing advances";
  d.keys("r");  // the tutorial starts in Camera mode, where R acts
  EXPECT_EQ(state.tutorialStep(), 1);
  d.keys("3");
  EXPECT_EQ(state.tutorialStep(), 1) << "Paint mode is not the Canvas mode asked for";
  d.keys("2");
  EXPECT_EQ(state.tutorialStep(), 2);
  d.keys("3");
  EXPECT_EQ(state.tutorialStep(), 3);
  d.keys("b");
  EXPECT_EQ(state.tutorialStep(), 4);
  EXPECT_EQ(rig.session->mode(), Mode::kPaint);
  d.keep("tutorial_stroke_step");
  d.stroke(referencePaintStrokes(kW, kH)[0]);
  d.frames(2);
  ASSERT_EQ(state.stage(), StudyStageKind::kTask) << state.waitingFor(d.now());

  // The task: an empty sky, the picture beside it, the countdown; one stroke, then time is up.
  EXPECT_EQ(state.task()->id, "cloud1");
  d.frames(1);
  d.keep("task");
  EXPECT_TRUE(d.labelShown("Time left 1:00") || d.labelShown("Time left 0:5"))
      << "a one-minute countdown";
  EXPECT_GT(rig.screen->page().image[2], rig.screen->page().image[0]) << "the reference picture";
  d.stroke(referencePaintStrokes(kW, kH)[1]);
  EXPECT_EQ(rig.session->strokesMapped(), 2u);
  d.frames(1, 61 * kSecond);
  d.frames(2);
  ASSERT_EQ(state.stage(), StudyStageKind::kDemographics) << state.waitingFor(d.now());

  // Demographics on the on-screen keyboard: an age out of range is refused and said so.
  d.tapKey("9");
  d.tap(StudyTargetAction::kOk);
  EXPECT_EQ(state.fieldIndex(), 0);
  d.keep("demographics_refused");
  EXPECT_TRUE(d.labelShown("whole number from 16 to 99"));
  d.tap(StudyTargetAction::kBackspace);
  d.tapKey("3");
  d.tapKey("4");
  d.tap(StudyTargetAction::kOk);
  ASSERT_EQ(state.fieldIndex(), 1);
  d.tapKey("f");
  d.keep("demographics_text");
  d.tap(StudyTargetAction::kOk);
  d.tap(StudyTargetAction::kSkipField);
  ASSERT_EQ(state.stage(), StudyStageKind::kQuestionnaire);

  // The questionnaire: one tap per item; item 5 skipped; the last is the lag item.
  const size_t items = rig.protocol.items.size();
  ASSERT_EQ(items, 28u);
  for (size_t i = 0; i < items; ++i) {
    ASSERT_EQ(state.itemIndex(), int(i));
    if (i == 0) d.keep("questionnaire");
    if (i == items - 1) {
      d.keep("questionnaire_lag_item");
      std::string lag = rig.protocol.items.back().text;  // shown without the *emphasis* marks
      lag.erase(std::remove(lag.begin(), lag.end(), '*'), lag.end());
      EXPECT_TRUE(d.labelShown(lag)) << lag;
      EXPECT_NE(lag.find("wait after each stroke"), std::string::npos) << "the lag item";
    }
    if (i == 4)
      d.tap(StudyTargetAction::kSkipItem);
    else
      d.tap(StudyTargetAction::kAnswer, int(i % 5) + 1);
  }
  ASSERT_EQ(state.stage(), StudyStageKind::kFreeText);
  // Free text beyond lowercase ASCII: Shift, the symbols page, the protocol's Chinese page
  // (bundled protocol's [keyboard]), then a physical keyboard's text (an input method's UTF-8)
  // and its BackSpace, which deletes one character (all of its bytes).
  d.tapKey("o");
  d.tapKey("k");
  d.tap(StudyTargetAction::kKeyboardPage, kKeyboardUpper);
  d.keep("free_text_shift");
  d.tapKey("K");
  d.tap(StudyTargetAction::kKeyboardPage, kKeyboardSymbols);
  d.keep("free_text_symbols");
  d.tapKey("\u20ac");  // €
  d.tap(StudyTargetAction::kKeyboardPage, kKeyboardProtocol);
  d.keep("free_text_chinese");
  d.tapKey("\u4e91");                                                      // 云
  const std::string typed = " \u00dcn\u00efc\u00f6d\u00e9 \u4e91 \u2601";  // " Ünïcödé 云 ☁"
  for (const std::string& text : {std::string(" \u00dcn\u00efc\u00f6d\u00e9 \u4e91 "),
                                  std::string("\u96fe"), std::string("\u2601")}) {
    DisplayEvent key = DisplayEvent::key(0x20);
    key.text = text;
    EXPECT_TRUE(rig.screen->onKey(key, d.now()));
    d.frames(1);
  }
  EXPECT_TRUE(rig.screen->onKey(DisplayEvent::key(0xff08), d.now()));  // BackSpace: the ☁
  EXPECT_TRUE(rig.screen->onKey(DisplayEvent::key(0xff08), d.now()));  // and the 雾
  DisplayEvent cloud = DisplayEvent::key(0x1002601);
  cloud.text = "\u2601";
  EXPECT_TRUE(rig.screen->onKey(cloud, d.now()));
  // The operator's Ctrl+Alt keys are not typed.
  EXPECT_FALSE(
      rig.screen->onKey(DisplayEvent::key('p', DisplayEvent::kCtrl | DisplayEvent::kAlt), d.now()));
  const std::string free_text = "okK\u20ac\u4e91" + typed;
  d.keep("free_text");
  EXPECT_TRUE(d.labelShown(free_text + "_")) << "the field shows what was typed";
  d.tap(StudyTargetAction::kOk);
  ASSERT_TRUE(state.done());
  d.keep("done");
  d.frames(200, kSecond / 10);
  EXPECT_EQ(d.quit(), "study complete");
  EXPECT_TRUE(rig.screen->problems().empty()) << rig.screen->problems().front();

  // The folder: answers as tapped, the journal's records, the task's files read back.
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

  // The journal replays (study markers are skipped) to the session's cloud.
  const SessionReplay replay =
      replaySession(readJournal(rig.folder + "/session.cbj"), rig.brush, rig.mapping);
  ASSERT_TRUE(replay.session);
  EXPECT_EQ(volumeChecksum(replay.session->volume()), volumeChecksum(volume));
  rig.screen.reset();
  std::filesystem::remove_all(rig.dir);
}

TEST(StudyRunScreen, OperatorPausesSkipsAndAbortsWithAReason) {
  Rig rig;
  if (!rig.open("cb_study_operator_")) return;
  Driver d(*rig.display, *rig.screen, rig.tablet, rig.t0);
  StudyRunState& state = *rig.state;
  d.frames(1);
  d.tap(StudyTargetAction::kAgree);
  // Pause: a reason by digit key; the participant's buttons wait; resume.
  d.keys("ctrl+alt+p");
  ASSERT_TRUE(state.choosing());
  d.keep("operator_chooser");
  EXPECT_TRUE(d.labelShown("Operator: why pause?"));
  d.keys("2");
  ASSERT_TRUE(state.paused());
  d.keep("paused");
  EXPECT_TRUE(d.labelShown("Paused by the operator (participant needs a break)"));
  d.keys("space");
  EXPECT_EQ(state.stage(), StudyStageKind::kParticipant) << "nothing moves while paused";
  d.keys("ctrl+alt+p");
  EXPECT_FALSE(state.paused());
  d.keys("space");
  ASSERT_EQ(state.stage(), StudyStageKind::kIntroduction);
  // Skip the introduction with a reason tapped by the pen; Esc cancels a chooser.
  d.keys("ctrl+alt+a");
  d.keys("esc");
  EXPECT_FALSE(state.choosing());
  EXPECT_FALSE(state.done());
  d.keys("ctrl+alt+s");
  d.tap(StudyTargetAction::kReason, 0);
  ASSERT_EQ(state.stage(), StudyStageKind::kTutorial);
  // Skip the steps (step 7, "Paint mode", holds already and passes by itself).
  for (int i = 0; i < 10 && state.stage() == StudyStageKind::kTutorial; ++i) d.keys("ctrl+alt+s,4");
  d.frames(2);
  ASSERT_EQ(state.stage(), StudyStageKind::kTask);
  // In the task, the clock stops while paused.
  d.frames(1, 10 * kSecond);
  const double left = state.secondsLeft(d.now());
  d.keys("ctrl+alt+p,1");
  d.frames(3, 100 * kSecond);
  EXPECT_EQ(state.stage(), StudyStageKind::kTask);
  EXPECT_NEAR(state.secondsLeft(d.now()), left, 0.5);
  d.keys("ctrl+alt+p");
  // Abort: the task's files are saved, then the session ends as aborted.
  d.keys("ctrl+alt+a");
  d.keep("operator_abort");
  d.tap(StudyTargetAction::kReason, 2);
  d.frames(2);
  ASSERT_TRUE(state.done());
  EXPECT_TRUE(state.aborted());
  d.keep("aborted");
  d.frames(50, kSecond / 10);
  EXPECT_EQ(d.quit(), "study aborted");
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
  Driver d(*rig.display, *rig.screen, rig.tablet, rig.t0);
  d.frames(1);
  d.tap(StudyTargetAction::kAgree);
  d.tap(StudyTargetAction::kContinue);
  d.keys("space");
  ASSERT_EQ(rig.state->stage(), StudyStageKind::kTutorial);
  d.keys("3");
  ASSERT_EQ(rig.state->tutorialStep(), 1);
  d.stroke(referencePaintStrokes(kW, kH)[0]);
  d.stroke(referencePaintStrokes(kW, kH)[1]);
  d.keys("c,m");
  ASSERT_EQ(rig.state->tutorialStep(), 1);
  TutorialState before = rig.screen->tutorialState();
  EXPECT_EQ(before.numbers["strokes_in_step"], 2);
  EXPECT_EQ(before.numbers["circles_shown"], 1);
  EXPECT_EQ(before.numbers["menu_open"], 1);
  d.keep("before_restart");

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
  StudyRunScreen resumed(*rig.display, rig.renderer, *replay.session, rig.pen.get(), nullptr, state,
                         options);
  Driver again(*rig.display, resumed, rig.tablet, restart);
  again.frames(1);
  ASSERT_EQ(state.stage(), StudyStageKind::kTutorial);
  ASSERT_EQ(state.tutorialStep(), 1);
  TutorialState after = resumed.tutorialState();
  EXPECT_EQ(after.numbers["strokes_in_step"], 2) << "the step's strokes carry on";
  EXPECT_EQ(after.numbers["circles_shown"], 1);
  EXPECT_EQ(after.numbers["menu_open"], 1);
  EXPECT_TRUE(resumed.paintScreen().menuOpen());
  EXPECT_TRUE(resumed.paintScreen().circlesShown());
  again.keep("resumed_tutorial_menu");
  again.keys("m");
  EXPECT_FALSE(resumed.paintScreen().menuOpen());
  again.keep("resumed_tutorial");
  EXPECT_TRUE(again.labelShown("strokes_in_step >= 4 (now 2, not yet)"));
  EXPECT_LT(state.stageSeconds(again.now()), 60.0) << "the 30 s down do not count";
  again.stroke(referencePaintStrokes(kW, kH)[0]);
  EXPECT_EQ(state.stage(), StudyStageKind::kTutorial) << "three of four";
  again.stroke(referencePaintStrokes(kW, kH)[1]);
  again.frames(2);
  EXPECT_NE(state.stage(), StudyStageKind::kTutorial) << "the fourth stroke ends the step";
  std::filesystem::remove_all(rig.dir);
}

}  // namespace
}  // namespace cb
