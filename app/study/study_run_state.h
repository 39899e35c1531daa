// The study runner's state machine (thesis §7.5): which stage of a protocol a session
// is in, what it waits for, the answers given, the operator's pauses, skips and aborts, and the
// journal records all of that leaves. Headless and clock-free: every call takes the time (ns,
// monotonic) from its caller, so tests drive it with any clock; the painter's screens
// (app/shell/study_*_screen) only show it and feed it.
//
// Stages, in order (a stage the protocol leaves empty is left out):
//   consent (agreed, or declined: the session ends there, nothing else recorded) → participant (the
//   pseudonymous id) → introduction → tutorial (one step at a time, each advancing when its check
//   holds in the live session state) → free drawing → tasks (in the participant's counterbalanced
//   order) → demographics → questionnaire (one Likert item at a time) → free text → done
// Timed stages: free drawing and tasks end when their time is up (the clock stops while paused
// or while the operator chooses a reason); a task also ends when the participant says they are
// done (finishTask: end reason `done`). A painting stage that ends (time up, done, skipped,
// aborted) first asks the runner to close it (`closing()`): the runner saves what the task says
// once no stroke is open, then calls closeStage().
//
// Operator: pause (again: resume), skip (the tutorial's current step, else the stage) and abort
// (the whole session) each ask for a reason from a short list (operatorReasons) before acting.
// Every stage change, tutorial step, answer and operator action is a record (takeRecords) that
// the runner writes to the session journal as a Marker, text `study.EVENT key=value ...`.
//
// Resuming (restarting on the same session folder resumes it): restore() rebuilds the
// state from those records as the journal holds them. The inputs among them (consent, continue,
// a tutorial step done, answers, the operator's requests and reasons, time up, saved files, a
// restart) are applied again at their recorded times; every other record must then be the one
// the state machine makes itself, so a journal of another protocol or participant is refused.
// resumedAfter() stops the stage clock over the time the runner was down.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/study/protocol.h"
#include "app/study/study_waiting_words.h"

namespace cb {

enum class StudyStageKind {
  kConsent,
  kParticipant,
  kIntroduction,
  kTutorial,
  kFreeDrawing,
  kTask,
  kDemographics,
  kQuestionnaire,
  kFreeText,
  kDone
};
const char* studyStageName(StudyStageKind kind);
// A countdown's "M:SS" for `seconds_left`, whole seconds rounded up: a ten-minute task starts
// at 10:00 and shows 0:00 only when its time is up.
std::string countdownText(double seconds_left);  // "consent", "participant", ...
// Stages where the participant paints (the painter's screen is shown).
bool isPaintingStage(StudyStageKind kind);

enum class OperatorAction { kPause, kSkip, kAbort };
const char* operatorActionName(OperatorAction action);  // "pause", "skip", "abort"
// The reasons offered for an action, in the order shown (digit keys 1..n choose them).
const std::vector<std::string>& operatorReasons(OperatorAction action);

struct StudyRunRecord {
  int64_t t_ns = 0;
  std::string text;  // `study.EVENT key=value ...` (values with spaces are quoted)
};

struct StudyStagePosition {
  StudyStageKind kind = StudyStageKind::kConsent;
  int task = -1;  // kTask: index into protocol.tasks
  int order = 0;  // kTask: position in the participant's order (0-based)
};

class StudyRunState {
 public:
  // `participant_number` >= 1 picks the id (participant_ids.h) and the task order.
  StudyRunState(const StudyProtocol& protocol, int participant_number, int64_t t_ns);

  const StudyProtocol& protocol() const { return protocol_; }
  const std::string& participantId() const { return participant_id_; }
  int participantNumber() const { return participant_number_; }
  StudyStageKind stage() const { return stages_[stage_index_].kind; }
  const StudyStagePosition& position() const { return stages_[stage_index_]; }
  // The current task (kTask), else null.
  const StudyTask* task() const;
  int taskCount() const { return int(task_order_.size()); }
  bool done() const { return stage() == StudyStageKind::kDone; }
  bool aborted() const { return aborted_; }
  // The participant declined consent: the session ended at the consent page.
  bool declined() const { return declined_; }
  const std::string& abortReason() const { return abort_reason_; }

  // --- participant
  void agree(int64_t t_ns);    // consent: "I agree"
  void decline(int64_t t_ns);  // consent: "I do not agree" (the session ends, declined)
  void proceed(int64_t t_ns);  // participant id and introduction: "Continue"
  // Tutorial: the live session state; true when the current step's check held and it advanced.
  bool observeTutorial(const TutorialState& state, int64_t t_ns);
  // The current tutorial step is done (its check held): the next step, or the stage closes.
  void completeTutorialStep(int64_t t_ns);
  int tutorialStep() const { return tutorial_step_; }  // 0-based, while in the tutorial
  // Questionnaire: answer `value` (1..scale) to the current item, then the next item.
  void answerItem(int value, int64_t t_ns);
  void skipItem(int64_t t_ns);  // the item stays NA
  void previousItem(int64_t t_ns);
  int itemIndex() const { return item_index_; }
  // Demographics: the current field's answer (validated: "" when taken, else what is wrong).
  std::string answerField(const std::string& text, int64_t t_ns);
  void skipField(int64_t t_ns);  // NA
  int fieldIndex() const { return field_index_; }
  // Free text: the current question's answer (empty: NA), then the next.
  void answerFreeText(const std::string& text, int64_t t_ns);
  int freeTextIndex() const { return free_text_index_; }

  // Task: the participant's "I'm done" (the task closes with the end reason `done`).
  void finishTask(int64_t t_ns);

  // --- time
  // Ends a timed painting stage whose time is up (it then waits in closing()).
  void tick(int64_t t_ns);
  // Seconds the current stage has run (the clock stopped while paused or choosing).
  double stageSeconds(int64_t t_ns) const;
  // The current stage's limit in seconds (0: none).
  double stageLimitSeconds() const;
  // Seconds left of a timed stage (clamped at 0), or -1 when the stage has no limit.
  double secondsLeft(int64_t t_ns) const;
  // A painting stage ended and waits for the runner to save and close it.
  bool closing() const { return closing_.has_value(); }
  const std::string& closingWhy() const { return closing_ ? *closing_ : empty_; }
  // `saved`: the task's files written; `pending`: those that could not be written yet (a full
  // disk; the runner writes them later). Both go into the `study.saved` record.
  void closeStage(int64_t t_ns, const std::vector<std::string>& saved = {},
                  const std::vector<std::string>& pending = {});

  // --- operator
  void requestOperator(OperatorAction action, int64_t t_ns);
  bool choosing() const { return choosing_.has_value(); }
  OperatorAction choosingFor() const { return choosing_.value_or(OperatorAction::kPause); }
  void chooseReason(int index, int64_t t_ns);  // 0-based into operatorReasons
  void cancelChoice(int64_t t_ns);
  bool paused() const { return paused_; }
  const std::string& pauseReason() const { return pause_reason_; }

  // What the screen waits for, in words (shown on every screen): English (logs, tests) and
  // English with Chinese (the page's foot line).
  std::string waitingFor(int64_t t_ns) const;
  StudyWords waitingWords(int64_t t_ns) const;

  std::vector<StudyRunRecord> takeRecords();

  // --- resuming
  // Re-applies `records` (a session journal's `study.*` markers, in order, the first being the
  // `study.session` record this constructor makes) to a state just constructed for the same
  // protocol and participant at the first record's time. Records the state machine made but the
  // journal lost (a crash between them) are queued again for takeRecords(). False with *error
  // naming the record that does not fit.
  bool restore(const std::vector<StudyRunRecord>& records, std::string* error);
  // After restore(): the index in its records of the current stage's `study.stage-begin`, or -1
  // when the journal lost it (the runner has not set the stage up yet).
  int restoredStageBegin() const { return restored_stage_begin_; }
  // After restore(): the last `study.step-progress` record (the runner's tutorial counters,
  // written by the screen, not by this state machine; restore() passes over them), or "".
  const std::string& restoredStepProgress() const { return restored_step_progress_; }
  // The runner restarted at `t_ns` after its last durable record at `last_record_ns`: the stage
  // clock does not count the time it was down (recorded as `study.resume down_ns=N`).
  void resumedAfter(int64_t last_record_ns, int64_t t_ns);
  // Stages that ended, in order: `consent`, ..., `task:ID` (session.json's stages_completed).
  const std::vector<std::string>& stagesCompleted() const { return stages_completed_; }

  // --- answers
  const std::vector<std::optional<int>>& itemAnswers() const { return items_; }
  const std::vector<std::optional<std::string>>& fieldAnswers() const { return fields_; }
  const std::vector<std::optional<std::string>>& freeTextAnswers() const { return free_texts_; }
  // questionnaire.csv: `participant,ITEM...` and one row (NA for missing); the format
  // likert_answers.h reads, so `study report` takes it as it is.
  std::string questionnaireCsv() const;
  // demographics.csv: `participant,FIELD...,FREE_TEXT...` and one row (NA for missing).
  std::string demographicsCsv() const;

 private:
  void record(int64_t t_ns, const std::string& text);
  void enterStage(size_t index, int64_t t_ns);
  void nextStage(int64_t t_ns, const std::string& how);
  void endPaintingStage(int64_t t_ns, const std::string& why);
  void suspend(int64_t t_ns);
  void resume(int64_t t_ns);
  bool applyInput(const StudyRunRecord& record, std::string* error);
  std::string stageLabel() const;

  const StudyProtocol& protocol_;
  int participant_number_;
  std::string participant_id_;
  std::vector<int> task_order_;
  std::vector<StudyStagePosition> stages_;
  size_t stage_index_ = 0;
  int64_t stage_start_ns_ = 0;
  int64_t suspended_ns_ = 0;                // clock stopped this long in the current stage
  std::optional<int64_t> suspended_since_;  // paused or choosing since
  int tutorial_step_ = 0;
  int item_index_ = 0, field_index_ = 0, free_text_index_ = 0;
  std::optional<std::string> closing_;
  std::optional<OperatorAction> choosing_;
  bool paused_ = false;
  std::string pause_reason_;
  bool aborted_ = false;
  bool declined_ = false;
  std::string abort_reason_;
  std::vector<std::optional<int>> items_;
  std::vector<std::optional<std::string>> fields_, free_texts_;
  std::vector<StudyRunRecord> records_;
  std::vector<std::string> stages_completed_;
  bool entered_ = false;
  int restored_stage_begin_ = -1;  // the first stage was entered (later entries leave one)
  std::string restored_step_progress_;
  std::string empty_;
};

}  // namespace cb
