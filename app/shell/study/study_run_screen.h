// `cloudbrush study run`: a study protocol (app/study/protocol.h) run as the shell's screens
// (thesis §7.5). One Screen for the frame loop that shows the runner's current stage:
// the form pages (consent, participant code, introduction, demographics, questionnaire, free
// text; app/shell/study/study_page.h) answered with pen taps (or a mouse), and in the tutorial,
// free drawing and tasks the painter's own screen (PaintScreen, composed, not changed) with the
// runner's panel beside it: the tutorial step and its live check, the task's reference image,
// the countdown.
//
// The state machine is app/study/study_run_state.h (headless); this screen feeds it taps, keys,
// the clock (FrameContext::now_ns, so tests drive time) and the live session state for the
// tutorial checks, writes its records to the journal as Marker records, and keeps the session
// folder (app/study/study_session_record.h) up to date: session.json at start, on each stage
// and at the end; questionnaire.csv and demographics.csv after every answer; each task's files
// when it ends (once no stroke is open).
//
// In a task the panel has an "I'm done" target (confirmed by a second tap: "Yes, I'm done"),
// which closes the task with the end reason `done`; the pen over the panel's targets is the
// panel's (journalled `pen_capture=on`, so the tap never paints), the mouse likewise. Consent
// has "I do not agree": the session ends there (session.json status "declined"; the answer
// files removed, so the folder holds session.json and the journal only).
//
// Keys: Space = "I agree" / "Continue"; 1-5 answer the questionnaire item (and choose the
// operator's reason); the painter's keys in painting stages. Operator: Ctrl+Alt+P pause/resume,
// Ctrl+Alt+S skip, Ctrl+Alt+A abort, each followed by a reason (tap or digit; Esc cancels).
// While the pen is on a form it is captured by the UI (journalled `pen_capture=on`), so taps
// never paint. Esc and q do not quit while the session runs; once it ended, the loop stops
// after `end_seconds` (or at Esc). The tutorial step's counters (strokes, brush changes,
// erasures, undos, saves in the step; the named view; the circle overlay) are journalled as a
// `study.step-progress` marker whenever they change, and a resumed session carries them on.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/render/hud_overlay.h"
#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"
#include "app/session/paint_session.h"
#include "app/shell/painter/paint_loop.h"
#include "app/shell/pen_events.h"
#include "app/shell/screen.h"
#include "app/shell/study/study_page.h"
#include "app/study/study_run_state.h"
#include "app/study/study_session_record.h"
#include "app/study/study_storage_watch.h"
#include "app/study/task_file_retry.h"
#include "app/study/tutorial_condition.h"
#include "calibration/mapped_sample.h"

namespace cb {

class PaintScreen;
class PenSource;
class UiOverlay;

struct StudyRunOptions {
  std::string folder;        // the session folder (created by the caller)
  PaintLoopOptions paint;    // the painter's options (render, config and state dirs)
  StudySessionInfo info;     // session.json's fixed part (protocol, participant, venue, ...)
  double end_seconds = 8.0;  // the closing page shows this long, then the loop ends
  // A resumed session (the state restored from the journal, the session replayed from it):
  // the stage is shown as it was; `set_up_stage` when the journal lost the stage's setup (a task
  // starts from an empty sky, Paint mode, the starting view), which is then done again.
  bool resumed = false;
  bool set_up_stage = false;
  int64_t start_ns = 0;  // the clock's time as the screen starts (the anchor when not resumed)
  // The journal's last pen sample as the session mapped it: a tap on a form that was under way
  // (tip down) goes on from there.
  std::optional<MappedSample> last_mapped;
  // Replay (`cloudbrush replay SESSION --frames`): the screen only shows a session that a replay
  // of its journal drives, and a state that the caller restores from the journal's markers as
  // their time comes. It then changes neither (no clock ticks, no task setup, no records) and
  // writes no file: `journal` is null and `folder` unused.
  bool replay_view = false;
};

class StudyRunScreen : public Screen {
 public:
  // `session` paints and journals (recordTo `journal` already); `pen` may be null (mouse only).
  StudyRunScreen(Display& display, VolumeRenderer& renderer, PaintSession& session, PenSource* pen,
                 JournalWriter* journal, StudyRunState& state, const StudyRunOptions& options);
  ~StudyRunScreen() override;

  const char* name() const override { return "study"; }
  void onPenSamples(const std::vector<PenSample>& samples) override;
  void onCommand(Command command, int64_t t_ns) override;
  // A form that takes text takes typed keys (a physical keyboard, an input method's UTF-8):
  // text is appended, BackSpace deletes a character, Return is OK. Ctrl/Alt keys (the
  // operator's) pass on.
  bool onKey(const DisplayEvent& event, int64_t t_ns) override;
  void onPointer(const DisplayEvent& event) override;
  void onResize(int width, int height) override;
  std::string update(const FrameContext& frame) override;
  bool draw(FrameContext& frame, std::string* error) override;
  void presented(const FrameContext& frame, double frame_ms) override;
  bool allowsQuit() const override { return state_.done(); }

  // The page drawn last (targets in screen pixels), for tests and logs.
  const StudyPage& page() const { return page_; }
  // The session state the tutorial checks see now.
  TutorialState tutorialState() const;
  // Problems met (files that could not be written), in order; empty when all went well.
  const std::vector<std::string>& problems() const { return problems_; }
  PaintScreen& paintScreen() { return *paint_; }

 private:
  void activate(const StudyTarget& target, int64_t t_ns);
  // The samples of one poll, each to the form or the painter (onPenSamples, once a frame drew).
  void feedSamples(const std::vector<PenSample>& samples);
  void formSample(const PenSample& sample);
  // A painting stage's sample: to the painter, or to the panel's targets while the pen is over
  // them (handed over only while the pen is up and no stroke is open).
  void paintingSample(const PenSample& sample);
  bool panelTargetAt(float x, float y) const;
  // What the page is laid out from besides the state (typed text, message, checks, the font).
  StudyPageInput pageInput() const;
  StudyPage currentPage(int width, int height) const;
  void tap(float x, float y, bool down, int64_t t_ns);
  void selectCalibration();
  void flushRecords();
  void afterStateChange(int64_t t_ns);
  void enterStage(int64_t t_ns);
  void setUpTask(int64_t t_ns);
  void saveTask(int64_t t_ns);
  // The running task's volume files written as it goes: at a stroke's end when the cloud
  // changed, at most every kSoFarNs (a runner killed mid-task leaves them; a resumed one writes
  // them at once from the replayed journal). The end frame (EXR, PNG) is rendered at the end.
  void writeTaskSoFar();
  static constexpr int64_t kSoFarNs = 2'000'000'000;
  uint64_t so_far_generation_ = 0;
  int64_t so_far_due_ns_ = 0;
  bool renderTaskFrame(ImageRgbaF* frame, std::string* error);
  void retryTaskFiles();
  void writeAnswers();
  void writeSessionJson();
  void observeSession();
  // The tutorial step's counters as a `study.step-progress` marker when they changed (so a
  // resumed session carries them on), and reading them back.
  void recordStepProgress();
  void restoreStepProgress(const std::string& text);
  std::string stepProgressText() const;
  bool loadReferenceImage(std::string* error);
  void problem(const std::string& text);

  Display& display_;
  VolumeRenderer& renderer_;
  PaintSession& session_;
  PenSource* pen_;
  JournalWriter* journal_;
  StudyRunState& state_;
  StudyRunOptions options_;
  TaskFileRetry task_files_;  // a task's files not written yet (kept, written again each second)
  std::unique_ptr<PaintScreen> paint_;
  std::unique_ptr<UiOverlay> ui_;
  HudOverlay hud_;
  bool hud_ready_ = false;
  StudyPage page_;
  // Samples polled before the first frame drew its page wait for it: a tap lands on the
  // targets where that frame draws them (its font measures the texts), not on an estimate.
  std::vector<PenSample> held_;
  bool page_drawn_ = false;
  std::string typed_, message_;
  int keyboard_page_ = kKeyboardLower;  // the on-screen keyboard's page
  // Writing to the session folder: outages for the operator and session.json; answer files and
  // session.json not written yet (written again each second).
  StudyStorageWatch storage_;
  bool files_pending_ = false;
  int64_t files_retry_ns_ = 0;
  std::string file_error_;
  void fileNotWritten(const std::string& error);
  void watchStorage();
  std::string glyphs_;      // typed text added to the font atlas
  std::string atlas_text_;  // the text whose characters the atlas holds (beyond Latin-1)
  bool atlasHolds(const std::string& text) const;
  static constexpr size_t kMaxTypedBytes = 500;  // a field's length limit (UTF-8 bytes)
  int64_t now_ns_ = 0;
  std::optional<int64_t> done_since_;

  // Pen on the forms
  PenEventDeriver pen_events_;
  std::vector<PenEvent> events_;
  int last_connection_ = -1;
  bool device_selected_ = false;  // the pen's device and calibration given to the session
  uint64_t tool_serial_ = 0;
  std::optional<StudyTarget> pressed_;  // the target under the pen (or mouse) when it went down
  bool mouse_down_ = false;
  bool panel_holds_pen_ = false;  // painting stage: the pen is over the panel's targets
  float form_pen_x_ = 0.0f, form_pen_y_ = 0.0f;
  bool done_asked_ = false;  // "I'm done" tapped: the panel asks to confirm
  // The task that ended last (its number in the order, from 1), said on the next page until
  // `saved_until_ns_`; `saved_pending_` while its files wait for the disk.
  int saved_task_ = 0;
  bool saved_pending_ = false;
  int64_t saved_until_ns_ = 0;
  static constexpr int64_t kSavedNoticeNs = 5'000'000'000;
  int saves_in_stage_ = 0;  // the painter's Saves in this stage (the save's answer counts them)
  std::string saveWords();

  // The stage the screen set up last (to notice changes)
  StudyStageKind last_stage_ = StudyStageKind::kDone;
  int last_task_ = -2, last_step_ = -1;

  // Tutorial observation: counters since the step was shown, derived from the session
  struct Observed {
    uint32_t strokes_mapped = 0;
    size_t undoable = 0;
    BrushKind brush = BrushKind::k2D;
    uint64_t generation = 0;
    size_t tapped = 0;
  } seen_;
  int64_t strokes_in_cloud_ = 0, strokes_in_step_ = 0, brush_changes_in_step_ = 0,
          erasures_in_step_ = 0, undos_in_step_ = 0, saves_in_step_ = 0;
  std::string camera_view_;
  Camera last_camera_;
  bool have_last_camera_ = false;
  bool circles_shown_ = false;
  std::string step_progress_;  // the last `study.step-progress` text journalled
  std::optional<Command> preset_pending_;
  bool cloud_empty_ = true;
  uint64_t empty_checked_generation_ = ~0ull;

  // The task's reference image
  RenderTarget image_;
  std::string image_path_;
  float image_aspect_ = 0.0f;

  std::vector<std::string> problems_;
};

}  // namespace cb
