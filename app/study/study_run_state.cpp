#include "app/study/study_run_state.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>

#include "app/study/csv_text.h"
#include "app/study/study_marker_text.h"

namespace cb {
namespace {

std::string quoted(const std::string& text) {
  return studyMarkerValue(text);
}

std::optional<OperatorAction> operatorActionFrom(const std::string& name) {
  for (OperatorAction a : {OperatorAction::kPause, OperatorAction::kSkip, OperatorAction::kAbort})
    if (name == operatorActionName(a)) return a;
  return std::nullopt;
}

std::string na(const std::optional<std::string>& v) {
  return v && !v->empty() ? csvField(*v) : "NA";
}

}  // namespace

const char* studyStageName(StudyStageKind kind) {
  switch (kind) {
    case StudyStageKind::kConsent:
      return "consent";
    case StudyStageKind::kParticipant:
      return "participant";
    case StudyStageKind::kIntroduction:
      return "introduction";
    case StudyStageKind::kTutorial:
      return "tutorial";
    case StudyStageKind::kFreeDrawing:
      return "free-drawing";
    case StudyStageKind::kTask:
      return "task";
    case StudyStageKind::kDemographics:
      return "demographics";
    case StudyStageKind::kQuestionnaire:
      return "questionnaire";
    case StudyStageKind::kFreeText:
      return "free-text";
    case StudyStageKind::kDone:
      return "done";
  }
  return "?";
}

bool isPaintingStage(StudyStageKind kind) {
  return kind == StudyStageKind::kTutorial || kind == StudyStageKind::kFreeDrawing ||
         kind == StudyStageKind::kTask;
}

const char* operatorActionName(OperatorAction action) {
  switch (action) {
    case OperatorAction::kPause:
      return "pause";
    case OperatorAction::kSkip:
      return "skip";
    case OperatorAction::kAbort:
      return "abort";
  }
  return "?";
}

const std::vector<std::string>& operatorReasons(OperatorAction action) {
  static const std::vector<std::string> pause = {"participant asked a question",
                                                 "participant needs a break", "technical problem",
                                                 "interruption", "other"};
  static const std::vector<std::string> skip = {"participant finished early",
                                                "participant is stuck", "technical problem",
                                                "out of session time", "other"};
  static const std::vector<std::string> abort = {"participant withdrew", "participant unwell",
                                                 "technical problem", "out of session time",
                                                 "other"};
  switch (action) {
    case OperatorAction::kPause:
      return pause;
    case OperatorAction::kSkip:
      return skip;
    case OperatorAction::kAbort:
      break;
  }
  return abort;
}

StudyRunState::StudyRunState(const StudyProtocol& protocol, int participant_number, int64_t t_ns)
    : protocol_(protocol),
      participant_number_(std::max(1, participant_number)),
      participant_id_(protocol.participant_ids.idFor(std::max(1, participant_number))),
      task_order_(taskOrderForParticipant(protocol.task_order, int(protocol.tasks.size()),
                                          std::max(1, participant_number))),
      items_(protocol.items.size()),
      fields_(protocol.demographics.size()),
      free_texts_(protocol.free_text.size()) {
  stages_.push_back({StudyStageKind::kConsent});
  stages_.push_back({StudyStageKind::kParticipant});
  if (!protocol.introduction.text.empty() || !protocol.introduction.video.empty())
    stages_.push_back({StudyStageKind::kIntroduction});
  if (!protocol.tutorial.empty()) stages_.push_back({StudyStageKind::kTutorial});
  if (!protocol.free_drawing.text.empty() || protocol.free_drawing.minutes > 0)
    stages_.push_back({StudyStageKind::kFreeDrawing});
  for (size_t i = 0; i < task_order_.size(); ++i)
    stages_.push_back({StudyStageKind::kTask, task_order_[i], int(i)});
  if (!protocol.demographics.empty()) stages_.push_back({StudyStageKind::kDemographics});
  if (!protocol.items.empty()) stages_.push_back({StudyStageKind::kQuestionnaire});
  if (!protocol.free_text.empty()) stages_.push_back({StudyStageKind::kFreeText});
  stages_.push_back({StudyStageKind::kDone});
  std::string order;
  for (int i : task_order_) order += (order.empty() ? "" : ",") + protocol.tasks[size_t(i)].id;
  record(t_ns, "study.session protocol=" + quoted(protocol.name) +
                   " version=" + quoted(protocol.version) + " participant=" + participant_id_ +
                   " number=" + std::to_string(participant_number_) + " task_order=" + order);
  enterStage(0, t_ns);
}

const StudyTask* StudyRunState::task() const {
  const StudyStagePosition& p = position();
  return p.kind == StudyStageKind::kTask ? &protocol_.tasks[size_t(p.task)] : nullptr;
}

void StudyRunState::record(int64_t t_ns, const std::string& text) {
  records_.push_back({t_ns, text});
}

std::vector<StudyRunRecord> StudyRunState::takeRecords() {
  std::vector<StudyRunRecord> out;
  out.swap(records_);
  return out;
}

std::string StudyRunState::stageLabel() const {
  std::string label = std::string("stage=") + studyStageName(stage());
  if (const StudyTask* t = task())
    label += " task=" + t->id + " position=" + std::to_string(position().order + 1);
  if (stage() == StudyStageKind::kTutorial) label += " step=" + std::to_string(tutorial_step_ + 1);
  return label;
}

void StudyRunState::enterStage(size_t index, int64_t t_ns) {
  if (entered_) {  // the stage being left (none when the constructor enters the first)
    std::string name = studyStageName(stage());
    if (const StudyTask* t = task()) name += ":" + t->id;
    stages_completed_.push_back(name);
  }
  entered_ = true;
  stage_index_ = index;
  stage_start_ns_ = t_ns;
  suspended_ns_ = 0;
  suspended_since_.reset();
  closing_.reset();
  tutorial_step_ = item_index_ = field_index_ = free_text_index_ = 0;
  if (stage() == StudyStageKind::kDone) {
    record(t_ns, std::string("study.end ") + (declined_  ? "declined"
                                              : aborted_ ? "aborted reason=" + quoted(abort_reason_)
                                                         : "completed"));
    return;
  }
  std::string text = "study.stage-begin " + stageLabel();
  if (const double limit = stageLimitSeconds(); limit > 0) text += " limit_s=" + csvDouble(limit);
  record(t_ns, text);
}

void StudyRunState::nextStage(int64_t t_ns, const std::string& how) {
  if (done()) return;
  record(t_ns, "study.stage-end " + stageLabel() + " how=" + quoted(how));
  enterStage(stage_index_ + 1, t_ns);
}

void StudyRunState::agree(int64_t t_ns) {
  if (stage() != StudyStageKind::kConsent || paused_ || choosing()) return;
  record(t_ns, "study.consent agreed=yes participant=" + participant_id_);
  nextStage(t_ns, "agreed");
}

void StudyRunState::decline(int64_t t_ns) {
  if (stage() != StudyStageKind::kConsent || paused_ || choosing()) return;
  declined_ = true;
  record(t_ns, "study.consent agreed=no participant=" + participant_id_);
  record(t_ns, "study.stage-end " + stageLabel() + " how=declined");
  enterStage(stages_.size() - 1, t_ns);
}

void StudyRunState::finishTask(int64_t t_ns) {
  if (stage() != StudyStageKind::kTask || paused_ || choosing() || closing()) return;
  endPaintingStage(t_ns, "done");
}

void StudyRunState::proceed(int64_t t_ns) {
  if (paused_ || choosing()) return;
  if (stage() == StudyStageKind::kParticipant || stage() == StudyStageKind::kIntroduction)
    nextStage(t_ns, "continue");
}

bool StudyRunState::observeTutorial(const TutorialState& state, int64_t t_ns) {
  if (stage() != StudyStageKind::kTutorial || paused_ || choosing() || closing()) return false;
  const TutorialStep& step = protocol_.tutorial[size_t(tutorial_step_)];
  for (const TutorialCondition& c : step.expect)
    if (!conditionHolds(c, state)) return false;
  completeTutorialStep(t_ns);
  return true;
}

void StudyRunState::completeTutorialStep(int64_t t_ns) {
  if (stage() != StudyStageKind::kTutorial || paused_ || choosing() || closing()) return;
  const TutorialStep& step = protocol_.tutorial[size_t(tutorial_step_)];
  record(t_ns, "study.tutorial-step done step=" + std::to_string(step.number) +
                   " seconds=" + csvDouble(stageSeconds(t_ns)));
  if (++tutorial_step_ >= int(protocol_.tutorial.size())) {
    tutorial_step_ = int(protocol_.tutorial.size()) - 1;
    endPaintingStage(t_ns, "all steps done");
  }
}

void StudyRunState::answerItem(int value, int64_t t_ns) {
  if (stage() != StudyStageKind::kQuestionnaire || paused_ || choosing()) return;
  const int scale = int(protocol_.scale_labels.size());
  if (value < 1 || value > scale) return;
  items_[size_t(item_index_)] = value;
  record(t_ns, "study.answer item=" + protocol_.items[size_t(item_index_)].id +
                   " value=" + std::to_string(value));
  if (++item_index_ >= int(items_.size())) {
    item_index_ = int(items_.size()) - 1;
    nextStage(t_ns, "answered");
  }
}

void StudyRunState::skipItem(int64_t t_ns) {
  if (stage() != StudyStageKind::kQuestionnaire || paused_ || choosing()) return;
  items_[size_t(item_index_)].reset();
  record(t_ns, "study.answer item=" + protocol_.items[size_t(item_index_)].id + " value=NA");
  if (++item_index_ >= int(items_.size())) {
    item_index_ = int(items_.size()) - 1;
    nextStage(t_ns, "answered");
  }
}

void StudyRunState::previousItem(int64_t t_ns) {
  (void)t_ns;
  if (stage() == StudyStageKind::kQuestionnaire && item_index_ > 0) --item_index_;
}

std::string StudyRunState::answerField(const std::string& text, int64_t t_ns) {
  if (stage() != StudyStageKind::kDemographics || paused_ || choosing()) return "";
  const DemographicField& field = protocol_.demographics[size_t(field_index_)];
  std::string value = text;
  while (!value.empty() && value.back() == ' ') value.pop_back();
  while (!value.empty() && value.front() == ' ') value.erase(value.begin());
  if (value.empty()) return "nothing entered: type an answer, or Skip";
  if (field.kind == DemographicField::Kind::kInteger) {
    errno = 0;
    char* end = nullptr;
    const long n = std::strtol(value.c_str(), &end, 10);
    if (errno != 0 || *end != '\0' || n < field.min || n > field.max)
      return "enter a whole number from " + std::to_string(field.min) + " to " +
             std::to_string(field.max);
    value = std::to_string(n);
  } else if (field.kind == DemographicField::Kind::kChoice &&
             std::find(field.choices.begin(), field.choices.end(), value) == field.choices.end()) {
    return "choose one of the listed answers";
  }
  fields_[size_t(field_index_)] = value;
  record(t_ns, "study.answer field=" + field.id + " value=" + quoted(value));
  if (++field_index_ >= int(fields_.size())) {
    field_index_ = int(fields_.size()) - 1;
    nextStage(t_ns, "answered");
  }
  return "";
}

void StudyRunState::skipField(int64_t t_ns) {
  if (stage() != StudyStageKind::kDemographics || paused_ || choosing()) return;
  fields_[size_t(field_index_)].reset();
  record(t_ns,
         "study.answer field=" + protocol_.demographics[size_t(field_index_)].id + " value=NA");
  if (++field_index_ >= int(fields_.size())) {
    field_index_ = int(fields_.size()) - 1;
    nextStage(t_ns, "answered");
  }
}

void StudyRunState::answerFreeText(const std::string& text, int64_t t_ns) {
  if (stage() != StudyStageKind::kFreeText || paused_ || choosing()) return;
  if (text.empty())
    free_texts_[size_t(free_text_index_)].reset();
  else
    free_texts_[size_t(free_text_index_)] = text;
  record(t_ns, "study.answer free_text=" + protocol_.free_text[size_t(free_text_index_)].id +
                   " value=" + (text.empty() ? std::string("NA") : quoted(text)));
  if (++free_text_index_ >= int(free_texts_.size())) {
    free_text_index_ = int(free_texts_.size()) - 1;
    nextStage(t_ns, "answered");
  }
}

double StudyRunState::stageSeconds(int64_t t_ns) const {
  int64_t stopped = suspended_ns_;
  if (suspended_since_) stopped += t_ns - *suspended_since_;
  return std::max(0.0, double(t_ns - stage_start_ns_ - stopped) / 1e9);
}

double StudyRunState::stageLimitSeconds() const {
  switch (stage()) {
    case StudyStageKind::kFreeDrawing:
      return protocol_.free_drawing.minutes * 60.0;
    case StudyStageKind::kTask:
      return task()->minutes * 60.0;
    default:
      return 0.0;
  }
}

double StudyRunState::secondsLeft(int64_t t_ns) const {
  const double limit = stageLimitSeconds();
  if (limit <= 0) return -1.0;
  return std::max(0.0, limit - stageSeconds(t_ns));
}

void StudyRunState::tick(int64_t t_ns) {
  if (closing() || !isPaintingStage(stage()) || paused_ || choosing()) return;
  const double limit = stageLimitSeconds();
  if (limit > 0 && stageSeconds(t_ns) >= limit) endPaintingStage(t_ns, "time up");
}

void StudyRunState::endPaintingStage(int64_t t_ns, const std::string& why) {
  closing_ = why;
  record(t_ns, "study.stage-closing " + stageLabel() + " why=" + quoted(why) +
                   " seconds=" + csvDouble(stageSeconds(t_ns)));
}

void StudyRunState::closeStage(int64_t t_ns, const std::vector<std::string>& saved,
                               const std::vector<std::string>& pending) {
  if (!closing_) return;
  const std::string why = *closing_;
  const auto joined = [](const std::vector<std::string>& files) {
    std::string list;
    for (const std::string& s : files) list += (list.empty() ? "" : ",") + s;
    return list;
  };
  if (!saved.empty() || !pending.empty())
    record(t_ns, "study.saved " + stageLabel() + " files=" + quoted(joined(saved)) +
                     (pending.empty() ? "" : " pending=" + quoted(joined(pending))));
  if (aborted_) {
    record(t_ns, "study.stage-end " + stageLabel() + " how=aborted");
    enterStage(stages_.size() - 1, t_ns);
    return;
  }
  nextStage(t_ns, why);
}

void StudyRunState::suspend(int64_t t_ns) {
  if (!suspended_since_) suspended_since_ = t_ns;
}

void StudyRunState::resume(int64_t t_ns) {
  if (suspended_since_ && !paused_ && !choosing_) {
    suspended_ns_ += t_ns - *suspended_since_;
    suspended_since_.reset();
  }
}

void StudyRunState::requestOperator(OperatorAction action, int64_t t_ns) {
  if (done() || choosing() || closing()) return;
  if (action == OperatorAction::kPause && paused_) {
    paused_ = false;
    record(t_ns, "study.operator action=resume " + stageLabel());
    resume(t_ns);
    return;
  }
  choosing_ = action;
  suspend(t_ns);
  record(t_ns, std::string("study.operator-request action=") + operatorActionName(action) + " " +
                   stageLabel());
}

void StudyRunState::cancelChoice(int64_t t_ns) {
  if (!choosing_) return;
  record(t_ns, std::string("study.operator-cancel action=") + operatorActionName(*choosing_) + " " +
                   stageLabel());
  choosing_.reset();
  resume(t_ns);
}

void StudyRunState::chooseReason(int index, int64_t t_ns) {
  if (!choosing_) return;
  const OperatorAction action = *choosing_;
  const std::vector<std::string>& reasons = operatorReasons(action);
  if (index < 0 || index >= int(reasons.size())) return;
  const std::string& reason = reasons[size_t(index)];
  choosing_.reset();
  record(t_ns, std::string("study.operator action=") + operatorActionName(action) +
                   " reason=" + quoted(reason) + " " + stageLabel());
  switch (action) {
    case OperatorAction::kPause:
      paused_ = true;
      pause_reason_ = reason;
      return;  // the clock stays stopped until the resume
    case OperatorAction::kSkip:
      resume(t_ns);
      if (stage() == StudyStageKind::kTutorial) {
        record(t_ns, "study.tutorial-step skipped step=" +
                         std::to_string(protocol_.tutorial[size_t(tutorial_step_)].number));
        if (++tutorial_step_ >= int(protocol_.tutorial.size())) {
          tutorial_step_ = int(protocol_.tutorial.size()) - 1;
          endPaintingStage(t_ns, "skipped: " + reason);
        }
      } else if (isPaintingStage(stage())) {
        endPaintingStage(t_ns, "skipped: " + reason);
      } else {
        nextStage(t_ns, "skipped: " + reason);
      }
      return;
    case OperatorAction::kAbort:
      resume(t_ns);
      aborted_ = true;
      abort_reason_ = reason;
      if (isPaintingStage(stage())) {
        endPaintingStage(t_ns, "aborted: " + reason);  // the task's files are still saved
      } else {
        record(t_ns, "study.stage-end " + stageLabel() + " how=aborted");
        enterStage(stages_.size() - 1, t_ns);
      }
      return;
  }
}

std::string countdownText(double seconds_left) {
  const int s = int(std::ceil(std::max(0.0, seconds_left) - 1e-9));  // 1 ns of float slack
  char text[32];
  std::snprintf(text, sizeof text, "%d:%02d", s / 60, s % 60);
  return text;
}

std::string StudyRunState::waitingFor(int64_t t_ns) const {
  return waitingWords(t_ns).en;
}

StudyWords StudyRunState::waitingWords(int64_t t_ns) const {
  using L = StudyWaitLine;
  if (choosing_) {
    const OperatorAction a = *choosing_;
    return studyWaitingWords(a == OperatorAction::kPause  ? L::kChoosePause
                             : a == OperatorAction::kSkip ? L::kChooseSkip
                                                          : L::kChooseAbort);
  }
  if (paused_) return studyWaitingWords(L::kPaused, {pause_reason_});
  if (closing_) return studyWaitingWords(L::kClosing, {*closing_});
  switch (stage()) {
    case StudyStageKind::kConsent:
      return studyWaitingWords(L::kConsent);
    case StudyStageKind::kParticipant:
      return studyWaitingWords(L::kParticipant, {participant_id_});
    case StudyStageKind::kIntroduction:
      return studyWaitingWords(L::kIntroduction);
    case StudyStageKind::kTutorial:
      return studyWaitingWords(L::kTutorial, {std::to_string(tutorial_step_ + 1),
                                              std::to_string(protocol_.tutorial.size())});
    case StudyStageKind::kFreeDrawing:
    case StudyStageKind::kTask: {
      const bool task = stage() == StudyStageKind::kTask;
      const double left = secondsLeft(t_ns);
      if (left < 0) return studyWaitingWords(task ? L::kTask : L::kPaint);
      return studyWaitingWords(task ? L::kTaskTimed : L::kPaintTimed, {countdownText(left)});
    }
    case StudyStageKind::kDemographics:
      return studyWaitingWords(L::kDemographics);
    case StudyStageKind::kQuestionnaire:
      return studyWaitingWords(L::kQuestionnaire);
    case StudyStageKind::kFreeText:
      return studyWaitingWords(L::kFreeText);
    case StudyStageKind::kDone:
      return studyWaitingWords(declined_ ? L::kDeclined : aborted_ ? L::kAborted : L::kDone);
  }
  return {};
}

void StudyRunState::resumedAfter(int64_t last_record_ns, int64_t t_ns) {
  const int64_t down = std::max<int64_t>(0, t_ns - last_record_ns);
  if (!suspended_since_) suspended_ns_ += down;  // (a pause already stopped the clock)
  record(t_ns, "study.resume down_ns=" + std::to_string(down) + " " + stageLabel());
}

bool StudyRunState::applyInput(const StudyRunRecord& r, std::string* error) {
  const StudyMarkerFields m = parseStudyMarker(r.text);
  const int64_t t = r.t_ns;
  const auto index_of = [&](const auto& list, const std::string& id) {
    for (size_t i = 0; i < list.size(); ++i)
      if (list[i].id == id) return int(i);
    return -1;
  };
  const auto missing = [&](const std::string& id) {
    return *error = "`" + r.text + "`: the protocol has no " + id, false;
  };
  const bool na = m.isNa("value");
  if (m.event == "study.consent") {
    if (m.get("agreed") == "no")
      decline(t);
    else
      agree(t);
  } else if (m.event == "study.stage-end") {
    if (closing())
      closeStage(t);
    else
      proceed(t);
  } else if (m.event == "study.tutorial-step" && !m.words.empty() && m.words[0] == "done") {
    completeTutorialStep(t);
  } else if (m.event == "study.answer" && m.has("item")) {
    const int i = index_of(protocol_.items, m.get("item"));
    if (i < 0) return missing("item " + m.get("item"));
    if (stage() == StudyStageKind::kQuestionnaire) item_index_ = i;
    if (na)
      skipItem(t);
    else
      answerItem(std::atoi(m.get("value").c_str()), t);
  } else if (m.event == "study.answer" && m.has("field")) {
    const int i = index_of(protocol_.demographics, m.get("field"));
    if (i < 0) return missing("demographic field " + m.get("field"));
    if (stage() == StudyStageKind::kDemographics) field_index_ = i;
    if (na) {
      skipField(t);
    } else if (const std::string refused = answerField(m.get("value"), t); !refused.empty()) {
      return *error = "`" + r.text + "`: " + refused, false;
    }
  } else if (m.event == "study.answer" && m.has("free_text")) {
    const int i = index_of(protocol_.free_text, m.get("free_text"));
    if (i < 0) return missing("free-text question " + m.get("free_text"));
    if (stage() == StudyStageKind::kFreeText) free_text_index_ = i;
    answerFreeText(na ? std::string() : m.get("value"), t);
  } else if (m.event == "study.operator-request" && operatorActionFrom(m.get("action"))) {
    requestOperator(*operatorActionFrom(m.get("action")), t);
  } else if (m.event == "study.operator" && m.get("action") == "resume") {
    if (paused_) requestOperator(OperatorAction::kPause, t);
  } else if (m.event == "study.operator" && operatorActionFrom(m.get("action"))) {
    const std::vector<std::string>& reasons = operatorReasons(*operatorActionFrom(m.get("action")));
    const auto it = std::find(reasons.begin(), reasons.end(), m.get("reason"));
    if (it == reasons.end()) return *error = "`" + r.text + "`: not one of the reasons", false;
    chooseReason(int(it - reasons.begin()), t);
  } else if (m.event == "study.operator-cancel") {
    cancelChoice(t);
  } else if (m.event == "study.stage-closing") {
    if (isPaintingStage(stage()) && !closing()) endPaintingStage(t, m.get("why"));
  } else if (m.event == "study.saved") {
    const auto split = [](const std::string& list) {
      std::vector<std::string> files;
      for (size_t at = 0; at <= list.size();) {
        const size_t comma = std::min(list.find(',', at), list.size());
        if (comma > at) files.push_back(list.substr(at, comma - at));
        at = comma + 1;
      }
      return files;
    };
    closeStage(t, split(m.get("files")), split(m.get("pending")));
  } else if (m.event == "study.resume") {
    const int64_t down = std::atoll(m.get("down_ns").c_str());
    resumedAfter(t - down, t);
  } else {
    return *error = "`" + r.text + "` is not a record the runner makes", false;
  }
  return true;
}

bool StudyRunState::restore(const std::vector<StudyRunRecord>& records, std::string* error) {
  std::deque<StudyRunRecord> expected;  // made by the state machine, not yet met in `records`
  for (StudyRunRecord& r : takeRecords()) expected.push_back(std::move(r));
  for (size_t i = 0; i < records.size(); ++i) {
    const StudyRunRecord& r = records[i];
    if (r.text.rfind("study.step-progress ", 0) == 0) {
      restored_step_progress_ = r.text;  // the screen's counters, not a state change
      continue;
    }
    if (r.text.rfind("study.files-written ", 0) == 0) continue;  // the screen's, after an outage
    const std::string where =
        "study record " + std::to_string(i + 1) + " (" + studyStageName(stage()) + ")";
    if (!expected.empty()) {
      if (expected.front().text != r.text) {
        *error = where + ": the journal holds `" + r.text + "` where this protocol makes `" +
                 expected.front().text + "`";
        return false;
      }
      expected.pop_front();
      if (r.text.rfind("study.stage-begin ", 0) == 0) restored_stage_begin_ = int(i);
      continue;
    }
    if (!applyInput(r, error)) return *error = where + ": " + *error, false;
    std::vector<StudyRunRecord> made = takeRecords();
    if (made.empty() || made.front().text != r.text) {
      *error = where + ": `" + r.text + "` " +
               (made.empty() ? std::string("does not apply here")
                             : "comes out as `" + made.front().text + "`");
      return false;
    }
    expected.assign(std::make_move_iterator(made.begin() + 1), std::make_move_iterator(made.end()));
  }
  for (const StudyRunRecord& r : expected)
    if (r.text.rfind("study.stage-begin ", 0) == 0) restored_stage_begin_ = -1;
  records_.assign(std::make_move_iterator(expected.begin()),
                  std::make_move_iterator(expected.end()));
  return true;
}

std::string StudyRunState::questionnaireCsv() const {
  std::string header = "participant", row = csvField(participant_id_);
  for (size_t i = 0; i < items_.size(); ++i) {
    header += "," + csvField(protocol_.items[i].id);
    row += "," + (items_[i] ? std::to_string(*items_[i]) : std::string("NA"));
  }
  return header + "\n" + row + "\n";
}

std::string StudyRunState::demographicsCsv() const {
  std::string header = "participant", row = csvField(participant_id_);
  for (size_t i = 0; i < fields_.size(); ++i) {
    header += "," + csvField(protocol_.demographics[i].id);
    row += "," + na(fields_[i]);
  }
  for (size_t i = 0; i < free_texts_.size(); ++i) {
    header += "," + csvField(protocol_.free_text[i].id);
    row += "," + na(free_texts_[i]);
  }
  return header + "\n" + row + "\n";
}

}  // namespace cb
