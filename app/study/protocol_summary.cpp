#include "app/study/protocol_summary.h"

#include <cstdio>
#include <filesystem>
#include <sstream>

namespace cb {
namespace {

std::string minutesText(double minutes) {
  if (minutes <= 0) return "no limit";
  char text[32];
  std::snprintf(text, sizeof text, "%g min", minutes);
  return text;
}

std::string kindName(ConditionKind kind) {
  switch (kind) {
    case ConditionKind::kWord:
      return "word";
    case ConditionKind::kInteger:
      return "integer";
    case ConditionKind::kBoolean:
      return "boolean";
  }
  return "?";
}

}  // namespace

std::string studyProtocolSummary(const StudyProtocol& p) {
  std::ostringstream out;
  out << p.source << ": valid\n";
  out << "study: " << p.name << (p.version.empty() ? "" : " (version " + p.version + ")") << "\n";
  out << "consent: " << p.consent.size() << " characters\n";
  const ParticipantIdScheme& ids = p.participant_ids;
  out << "participant ids: "
      << (ids.kind == ParticipantIdScheme::Kind::kCounter ? "counter" : "random") << ", e.g. "
      << ids.idFor(1) << ", " << ids.idFor(2)
      << "; key file: " << (ids.key_file.empty() ? "none" : ids.key_file) << "\n";
  out << "venues:";
  for (const StudyVenue& venue : p.venues) out << " " << venue.id;
  out << "; operator " << (p.operator_required ? "required" : "optional") << "\n";
  out << "introduction: " << minutesText(p.introduction.minutes)
      << (p.introduction.video.empty() ? "" : ", video " + p.introduction.video) << "\n";
  out << "tutorial: " << p.tutorial.size() << " steps, " << minutesText(p.tutorial_minutes) << "\n";
  for (const TutorialStep& step : p.tutorial) {
    out << "  " << step.number << ". " << step.instruction << "  [";
    for (size_t k = 0; k < step.expect.size(); ++k)
      out << (k ? " and " : "") << step.expect[k].text();
    out << "]\n";
  }
  out << "free drawing: " << minutesText(p.free_drawing.minutes)
      << (p.free_drawing.questions_allowed ? ", questions welcome" : ", no questions") << "\n";
  out << "tasks: " << p.tasks.size() << ", order " << counterbalanceSchemeName(p.task_order)
      << (p.task_questions_allowed ? ", questions allowed" : ", no questions") << "\n";
  for (const StudyTask& task : p.tasks) {
    out << "  " << task.id << ": " << task.title << " (" << minutesText(task.minutes) << "; image "
        << task.image << "; saves";
    for (TaskSaveKind kind : task.save) out << " " << taskSaveKindName(kind);
    out << ")\n";
  }
  const int cycle = counterbalanceCycle(p.task_order, int(p.tasks.size()));
  out << "task orders (a cycle of " << cycle << " participant" << (cycle == 1 ? "" : "s") << "):\n";
  for (int n = 1; n <= cycle; ++n) {
    out << "  " << ids.idFor(n) << ":";
    for (const StudyTask* task : p.tasksForParticipant(n)) out << " " << task->id;
    out << "\n";
  }
  out << "demographics:";
  for (const DemographicField& field : p.demographics) out << " " << field.id;
  out << "\nquestionnaire: " << p.items.size() << " items on a " << p.scale_labels.size()
      << "-point scale (" << p.scale_labels.front() << " .. " << p.scale_labels.back() << "), "
      << p.free_text.size() << " free-text question" << (p.free_text.size() == 1 ? "" : "s")
      << "\n";
  for (const ProtocolConstruct& construct : p.constructs) {
    out << "  construct " << construct.name << ":";
    for (const std::string& item : construct.items) out << " " << item;
    out << "\n";
  }
  return out.str();
}

std::string tutorialVocabularyText() {
  std::ostringstream out;
  for (const TutorialVariable& variable : tutorialVariables()) {
    out << variable.name << " (" << kindName(variable.kind);
    if (!variable.words.empty()) {
      out << ":";
      for (std::string_view word : variable.words) out << " " << word;
    }
    out << ") " << variable.meaning << "\n";
  }
  return out.str();
}

std::vector<std::string> missingProtocolFiles(const StudyProtocol& p) {
  std::vector<std::string> missing;
  std::error_code ec;
  const auto check = [&](const std::string& field, const std::string& path) {
    if (!path.empty() && !std::filesystem::is_regular_file(path, ec))
      missing.push_back(field + ": " + path);
  };
  check("introduction.video", p.introduction.video);
  check("free_drawing.video", p.free_drawing.video);
  for (size_t i = 0; i < p.tasks.size(); ++i)
    check("task[" + std::to_string(i + 1) + "].image", p.tasks[i].image);
  return missing;
}

}  // namespace cb
