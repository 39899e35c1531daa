// A user-study protocol (thesis ch. 7): everything a study session follows, read from
// one TOML file and checked completely before any session starts. The bundled default is the
// thesis's study, config/study/thesis_2014.toml, which documents every table and field; the
// format in short:
//
//   [study]         name, version (text)
//   [consent]       text (shown and agreed to first, §7.5)
//   [participants]  id_scheme = "counter" (prefix, digits) | "random" (prefix, seed, length);
//                   key_file (optional, absolute; participant_ids.h)
//   [[venue]]       id, name                                  (two venues in §7.4)
//   [operator]      required (the operator's initials are asked at session start)
//   [introduction]  text, video (optional path), minutes (optional)          (§7.5 stage 1)
//   [tutorial]      minutes; [[tutorial.step]] instruction, expect = ["NAME OP VALUE", ...]
//                   (tutorial_condition.h; default: Appendix A's 26 steps)      (§7.5 stage 2)
//   [free_drawing]  text, minutes (optional), questions_allowed                 (§7.5 stage 2)
//   [tasks]         order = "fixed" | "rotation" | "williams" (counterbalancing.h),
//                   minutes (default time limit, 10 if absent), questions_allowed
//   [[task]]        id, title, image (relative to the protocol file), minutes (optional),
//                   save = ["journal", "volume_vdb", "volume_raw", "render_exr", "render_png"]
//                   (Appendix B; §7.5 stage 3)
//   [[demographic]] id, label, kind = "integer" (min, max) | "text" | "choice" (choices)
//   [questionnaire] scale = ["strongly disagree", ..., "strongly agree"] (values 1..n),
//                   scale_zh (optional: the same labels in Chinese)
//   [[item]]        id, text, text_zh (optional: in Chinese), section (optional), origin
//                   (optional)                                               (Appendix C)
//   [[free_text]]   id, prompt (optional answers)
//   [keyboard]      label (the on-screen keyboard's key for the page), keys = ["云", "，", ...]
//                   (optional: at most 40 keys, each typing its text — characters or words of
//                   the protocol's language a participant's answers need)
//   [[construct]]   name, items (declared item ids; construct_definitions.h)
//
// Unknown tables and fields are errors (a typo must not silently drop a setting). Every error
// is a StudyProtocolError "FILE:LINE: FIELD: what", FIELD a path like task[2].minutes.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "app/study/counterbalancing.h"
#include "app/study/participant_ids.h"
#include "app/study/tutorial_condition.h"

namespace cb {

class StudyProtocolError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct StudyVenue {
  std::string id, name;
};

struct StudyStage {
  std::string text;
  std::string video;   // optional path (resolved against the protocol's folder)
  double minutes = 0;  // 0: no limit
  bool questions_allowed = true;
};

struct TutorialStep {
  int number = 0;  // 1-based, as shown
  std::string instruction;
  std::vector<TutorialCondition> expect;  // all must hold
};

enum class TaskSaveKind { kJournal, kVolumeVdb, kVolumeRaw, kRenderExr, kRenderPng };
std::string_view taskSaveKindName(TaskSaveKind kind);

struct StudyTask {
  std::string id, title;
  std::string image;  // resolved against the protocol's folder
  double minutes = 10;
  std::vector<TaskSaveKind> save;
};

struct DemographicField {
  enum class Kind { kInteger, kText, kChoice };
  std::string id, label;
  Kind kind = Kind::kText;
  long min = 0, max = 0;             // kInteger
  std::vector<std::string> choices;  // kChoice
};

struct QuestionnaireItem {
  std::string id, text, section, origin;
  std::string text_zh;  // the statement in Chinese, or ""
};

struct FreeTextQuestion {
  std::string id, prompt;
};

// The on-screen keyboard's page of the protocol's own characters (none when keys is empty).
struct StudyKeyboardPage {
  std::string label;
  std::vector<std::string> keys;
};
inline constexpr size_t kMaxKeyboardKeys = 40;

struct ProtocolConstruct {
  std::string name;
  std::vector<std::string> items;
};

struct StudyProtocol {
  std::string source;  // the file it was read from
  std::string name, version;
  std::string consent;
  ParticipantIdScheme participant_ids;
  std::vector<StudyVenue> venues;
  bool operator_required = true;
  StudyStage introduction;
  double tutorial_minutes = 10;
  std::vector<TutorialStep> tutorial;
  StudyStage free_drawing;
  CounterbalanceScheme task_order = CounterbalanceScheme::kFixed;
  bool task_questions_allowed = false;
  std::vector<StudyTask> tasks;
  std::vector<DemographicField> demographics;
  std::vector<std::string> scale_labels;     // answer k (1-based) is scale_labels[k-1]
  std::vector<std::string> scale_labels_zh;  // the same in Chinese (empty: none given)
  std::vector<QuestionnaireItem> items;
  std::vector<FreeTextQuestion> free_text;
  StudyKeyboardPage keyboard;
  std::vector<ProtocolConstruct> constructs;

  // Participant `number`'s (>= 1) tasks in the order they take them.
  std::vector<const StudyTask*> tasksForParticipant(int number) const;
};

// `source` names the text in errors; relative paths resolve against its folder.
StudyProtocol parseStudyProtocol(std::string_view text, const std::string& source);
StudyProtocol loadStudyProtocol(const std::string& path);

// The bundled default: configFile("study/thesis_2014.toml").
std::string defaultStudyProtocolPath();

}  // namespace cb
