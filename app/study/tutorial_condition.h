// A tutorial step's check: a small declared vocabulary of session-state names compared with a
// value, written `NAME OP VALUE` (e.g. `mode == canvas`, `strokes >= 1`,
// `canvas_altitude == 96`). A step passes when every one of its conditions holds.
//
// The vocabulary (kTutorialVariables) is everything a check may name; the study runner fills a
// TutorialState from the painter's session each frame. Counters named `*_in_step` count from the
// moment the step was shown. Kinds:
//   word    compared with == or != against one of the variable's listed words
//   integer compared with == != < <= > >= against a decimal integer
//   boolean compared with == or != against true or false
// Anything else (an unknown name, an operator the kind does not allow, a word not listed, a
// number out of range) is a TutorialConditionError saying which part is wrong.
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace cb {

enum class ConditionKind { kWord, kInteger, kBoolean };

struct TutorialVariable {
  std::string_view name;
  ConditionKind kind;
  std::vector<std::string_view> words;  // kWord: the values it can take
  std::string_view meaning;
};

// The declared vocabulary, in the order `study check` lists it.
const std::vector<TutorialVariable>& tutorialVariables();
const TutorialVariable* findTutorialVariable(std::string_view name);

enum class ConditionOperator { kEqual, kNotEqual, kLess, kLessEqual, kGreater, kGreaterEqual };

struct TutorialCondition {
  std::string variable;
  ConditionOperator op = ConditionOperator::kEqual;
  // kWord: the word; kBoolean: "true"/"false"; kInteger: unused.
  std::string word;
  int64_t number = 0;  // kInteger, and kBoolean as 0/1
  ConditionKind kind = ConditionKind::kWord;

  std::string text() const;  // canonical `NAME OP VALUE`
};

class TutorialConditionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

TutorialCondition parseTutorialCondition(std::string_view text);

// The session state a check is evaluated against: words and integers by variable name (booleans
// as 0/1 integers). A variable the state lacks makes the condition false.
struct TutorialState {
  std::map<std::string, std::string, std::less<>> words;
  std::map<std::string, int64_t, std::less<>> numbers;
};

bool conditionHolds(const TutorialCondition& condition, const TutorialState& state);

}  // namespace cb
