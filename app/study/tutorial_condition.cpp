#include "app/study/tutorial_condition.h"

#include <charconv>

namespace cb {
namespace {

std::string_view trim(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  return text;
}

struct OperatorSpelling {
  std::string_view text;
  ConditionOperator op;
};
// Two-character spellings first so `<=` is not read as `<`.
constexpr OperatorSpelling kOperators[] = {
    {"==", ConditionOperator::kEqual},     {"!=", ConditionOperator::kNotEqual},
    {"<=", ConditionOperator::kLessEqual}, {">=", ConditionOperator::kGreaterEqual},
    {"<", ConditionOperator::kLess},       {">", ConditionOperator::kGreater}};

std::string_view operatorText(ConditionOperator op) {
  for (const OperatorSpelling& spelling : kOperators)
    if (spelling.op == op) return spelling.text;
  return "?";
}

bool isName(std::string_view text) {
  if (text.empty()) return false;
  for (char c : text)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
  return true;
}

}  // namespace

const std::vector<TutorialVariable>& tutorialVariables() {
  static const std::vector<TutorialVariable> variables = {
      {"mode",
       ConditionKind::kWord,
       {"camera", "canvas", "paint", "erase", "light"},
       "the painter's mode (keys 1-5)"},
      {"camera_view",
       ConditionKind::kWord,
       {"reset", "top", "front", "left", "perspective", "free"},
       "the last camera preset: R (reset), Up/Down/Left/Right; free after orbiting"},
      {"camera_elevation_deg",
       ConditionKind::kInteger,
       {},
       "degrees the view looks down from the horizon (90: straight down)"},
      {"canvas_altitude", ConditionKind::kInteger, {}, "canvas altitude in voxels"},
      {"brush", ConditionKind::kWord, {"2d", "3d", "skeleton"}, "the selected brush"},
      {"erase_tool", ConditionKind::kWord, {"vacuum", "rub-out"}, "the selected erase tool"},
      {"strokes",
       ConditionKind::kInteger,
       {},
       "strokes in the cloud (undo and delete remove them)"},
      {"cloud_empty", ConditionKind::kBoolean, {}, "the volume holds no density"},
      {"circles_shown", ConditionKind::kBoolean, {}, "the circle-growth overlay is shown (C)"},
      {"menu_open", ConditionKind::kBoolean, {}, "the pen menu is open"},
      {"strokes_in_step", ConditionKind::kInteger, {}, "strokes painted since the step was shown"},
      {"brush_changes_in_step",
       ConditionKind::kInteger,
       {},
       "brush changes since the step was shown"},
      {"erasures_in_step",
       ConditionKind::kInteger,
       {},
       "erase actions (rub-out strokes, vacuum cuts) since the step was shown"},
      {"undos_in_step", ConditionKind::kInteger, {}, "undos since the step was shown"},
      {"saves_in_step", ConditionKind::kInteger, {}, "saves to file since the step was shown"},
  };
  return variables;
}

const TutorialVariable* findTutorialVariable(std::string_view name) {
  for (const TutorialVariable& variable : tutorialVariables())
    if (variable.name == name) return &variable;
  return nullptr;
}

std::string TutorialCondition::text() const {
  std::string value = kind == ConditionKind::kInteger ? std::to_string(number) : word;
  return variable + " " + std::string(operatorText(op)) + " " + value;
}

TutorialCondition parseTutorialCondition(std::string_view text) {
  text = trim(text);
  size_t at = std::string_view::npos;
  const OperatorSpelling* found = nullptr;
  for (const OperatorSpelling& spelling : kOperators) {
    const size_t position = text.find(spelling.text);
    if (position != std::string_view::npos && (at == std::string_view::npos || position < at ||
                                               (position == at && spelling.text.size() == 2))) {
      at = position;
      found = &spelling;
    }
  }
  if (!found)
    throw TutorialConditionError("'" + std::string(text) +
                                 "': expected NAME OP VALUE with OP one of == != < <= > >=");
  const std::string_view name = trim(text.substr(0, at));
  const std::string_view value = trim(text.substr(at + found->text.size()));
  if (!isName(name))
    throw TutorialConditionError("'" + std::string(text) + "': '" + std::string(name) +
                                 "' is not a variable name");
  const TutorialVariable* variable = findTutorialVariable(name);
  if (!variable)
    throw TutorialConditionError("'" + std::string(name) +
                                 "' is not in the vocabulary (see `cloudbrush study check "
                                 "--vocabulary`)");
  TutorialCondition condition;
  condition.variable = std::string(name);
  condition.op = found->op;
  condition.kind = variable->kind;
  const bool ordering =
      found->op != ConditionOperator::kEqual && found->op != ConditionOperator::kNotEqual;
  switch (variable->kind) {
    case ConditionKind::kWord: {
      if (ordering) throw TutorialConditionError("'" + std::string(name) + "' takes only == or !=");
      bool listed = false;
      std::string choices;
      for (std::string_view word : variable->words) {
        listed = listed || word == value;
        choices += (choices.empty() ? "" : ", ") + std::string(word);
      }
      if (!listed)
        throw TutorialConditionError("'" + std::string(name) + "' cannot be '" +
                                     std::string(value) + "' (one of: " + choices + ")");
      condition.word = std::string(value);
      break;
    }
    case ConditionKind::kBoolean:
      if (ordering) throw TutorialConditionError("'" + std::string(name) + "' takes only == or !=");
      if (value != "true" && value != "false")
        throw TutorialConditionError("'" + std::string(name) + "' is true or false, not '" +
                                     std::string(value) + "'");
      condition.word = std::string(value);
      condition.number = value == "true" ? 1 : 0;
      break;
    case ConditionKind::kInteger: {
      int64_t number = 0;
      const char* end = value.data() + value.size();
      const auto result = std::from_chars(value.data(), end, number);
      if (value.empty() || result.ec != std::errc() || result.ptr != end || number < -1000000 ||
          number > 1000000)
        throw TutorialConditionError("'" + std::string(name) +
                                     "' is compared with an integer (-1000000..1000000), not '" +
                                     std::string(value) + "'");
      condition.number = number;
      break;
    }
  }
  return condition;
}

bool conditionHolds(const TutorialCondition& condition, const TutorialState& state) {
  if (condition.kind == ConditionKind::kWord) {
    const auto it = state.words.find(condition.variable);
    if (it == state.words.end()) return false;
    const bool equal = it->second == condition.word;
    return condition.op == ConditionOperator::kEqual ? equal : !equal;
  }
  const auto it = state.numbers.find(condition.variable);
  if (it == state.numbers.end()) return false;
  const int64_t have = it->second, want = condition.number;
  switch (condition.op) {
    case ConditionOperator::kEqual:
      return have == want;
    case ConditionOperator::kNotEqual:
      return have != want;
    case ConditionOperator::kLess:
      return have < want;
    case ConditionOperator::kLessEqual:
      return have <= want;
    case ConditionOperator::kGreater:
      return have > want;
    case ConditionOperator::kGreaterEqual:
      return have >= want;
  }
  return false;
}

}  // namespace cb
