#include "app/study/tutorial_words.h"

namespace cb {
namespace {

struct Words {
  const char* en;
  const char* zh;
};

// How a word-variable's values read (the painter's menu names modes and tools the same way,
// app/shell/command_table.cpp).
struct WordName {
  std::string_view variable, word;
  Words name;
};
constexpr WordName kWordNames[] = {
    {"mode", "camera", {"Camera mode", "相机模式"}},
    {"mode", "canvas", {"Canvas mode", "画布模式"}},
    {"mode", "paint", {"Paint mode", "绘画模式"}},
    {"mode", "erase", {"Erase mode", "擦除模式"}},
    {"mode", "light", {"Light mode", "光照模式"}},
    {"camera_view", "reset", {"the starting view", "初始视角"}},
    {"camera_view", "top", {"the top view", "俯视图"}},
    {"camera_view", "front", {"the front view", "正视图"}},
    {"camera_view", "left", {"the left view", "左视图"}},
    {"camera_view", "perspective", {"the 3/4 view", "斜视图"}},
    {"camera_view", "free", {"a view of your own", "自由视角"}},
    {"brush", "2d", {"2D", "二维"}},
    {"brush", "3d", {"3D", "三维"}},
    {"brush", "skeleton", {"skeleton", "骨架"}},
    {"erase_tool", "vacuum", {"Vacuum", "吸除"}},
    {"erase_tool", "rub-out", {"Rub-out", "擦拭"}},
};

// One wording a variable. Word variables: `want` for `== w`, `other` for `!= w` (%w: the word's
// name). Booleans: `want` for true, `other` for false. Integers: `want` for `OP n` (%q: the
// quantity, "4" or "at least 4"; the Chinese template puts no space before it), `other` for the
// quantity one when the variable counts ("Paint one stroke"); `counts` when it counts up (its plain
// comparison `>=`, its status "k of n so far"), otherwise it is a setting (plain `==`, status "now
// k"); `unit` follows a setting's value.
struct VariableWording {
  std::string_view variable;
  Words want, other;
  bool counts = false;
  Words unit = {"", ""};
};
constexpr VariableWording kVariables[] = {
    {"mode", {"Switch to %w", "切换到%w"}, {"Leave %w", "离开%w"}},
    {"camera_view",
     {"Turn the camera to %w", "把相机转到%w"},
     {"Turn the camera away from %w", "把相机从%w转开"}},
    {"camera_elevation_deg",
     {"Tilt the view down to %q degrees", "把视角向下倾斜到%q 度"},
     {nullptr, nullptr},
     false,
     {" degrees", " 度"}},
    {"canvas_altitude", {"Set the canvas altitude to %q", "把画布高度调到%q"}, {nullptr, nullptr}},
    {"brush",
     {"Choose the %w brush", "选择%w笔刷"},
     {"Choose a brush other than %w", "选择%w以外的笔刷"}},
    {"erase_tool",
     {"Choose the %w erase tool", "选择%w擦除工具"},
     {"Choose an erase tool other than %w", "选择%w以外的擦除工具"}},
    {"strokes",
     {"Have %q strokes in the cloud", "让云里有%q 笔"},
     {"Have one stroke in the cloud", "让云里有一笔"},
     true},
    {"cloud_empty",
     {"Clear the cloud", "清空云"},
     {"Paint something in the cloud", "在云里画点东西"}},
    {"circles_shown",
     {"Show the circle growth", "显示圆圈生长"},
     {"Hide the circle growth", "隐藏圆圈生长"}},
    {"menu_open", {"Open the pen menu", "打开笔的菜单"}, {"Close the pen menu", "关闭笔的菜单"}},
    {"strokes_in_step", {"Paint %q strokes", "画%q 笔"}, {"Paint one stroke", "画一笔"}, true},
    {"brush_changes_in_step",
     {"Change the brush %q times", "换%q 次笔刷"},
     {"Change the brush", "换一次笔刷"},
     true},
    {"erasures_in_step", {"Erase %q times", "擦除%q 次"}, {"Erase once", "擦除一次"}, true},
    {"undos_in_step", {"Undo %q times", "撤销%q 次"}, {"Undo once", "撤销一次"}, true},
    {"saves_in_step",
     {"Save to file %q times", "保存到文件%q 次"},
     {"Save to file", "保存到文件"},
     true},
};

// An integer's quantity by comparison (%n: the number); a variable's plain comparison (`>=` for
// counts, `==` for settings) reads as the bare number.
struct Quantity {
  ConditionOperator op;
  Words words;
};
constexpr Quantity kQuantities[] = {
    {ConditionOperator::kEqual, {"exactly %n", "正好 %n"}},
    {ConditionOperator::kNotEqual, {"other than %n", "不等于 %n"}},
    {ConditionOperator::kLess, {"less than %n", "少于 %n"}},
    {ConditionOperator::kLessEqual, {"at most %n", "最多 %n"}},
    {ConditionOperator::kGreater, {"more than %n", "多于 %n"}},
    {ConditionOperator::kGreaterEqual, {"at least %n", "至少 %n"}},
};

// Where the session stands (%k: its value now, %n: the number asked for).
constexpr Words kDone{"done", "已完成"};
constexpr Words kNotYet{"not yet", "还没有"};
constexpr Words kSoFar{"%k of %n so far", "目前 %k / %n"};
constexpr Words kNow{"now %k", "现在是%k"};  // a Chinese number comes spaced
// A check the table cannot word.
constexpr Words kFallback{"Do the step's task", "完成这一步的任务"};

std::string replaced(std::string text, std::string_view key, const std::string& value) {
  for (size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + value.size()))
    text.replace(at, key.size(), value);
  return text;
}

StudyWords fill(const StudyWords& words, std::string_view key, const StudyWords& value) {
  return {replaced(words.en, key, value.en), replaced(words.zh, key, value.zh)};
}
StudyWords fill(const Words& words, std::string_view key, const StudyWords& value) {
  return fill(StudyWords{words.en, words.zh}, key, value);
}

const VariableWording* findWording(std::string_view variable) {
  for (const VariableWording& v : kVariables)
    if (v.variable == variable) return &v;
  return nullptr;
}

const WordName* findWordName(std::string_view variable, std::string_view word) {
  for (const WordName& n : kWordNames)
    if (n.variable == variable && n.word == word) return &n;
  return nullptr;
}

bool plainOperator(const VariableWording& v, ConditionOperator op) {
  return op == (v.counts ? ConditionOperator::kGreaterEqual : ConditionOperator::kEqual);
}

StudyWords integerGoal(const VariableWording& v, const TutorialCondition& c) {
  const std::string n = std::to_string(c.number);
  if (v.counts && plainOperator(v, c.op) && c.number == 1 && v.other.en)
    return {v.other.en, v.other.zh};
  StudyWords quantity{n, " " + n};  // the Chinese number spaced from the verb before it
  if (!plainOperator(v, c.op))
    for (const Quantity& q : kQuantities)
      if (q.op == c.op) quantity = fill(q.words, "%n", {n, n});
  return fill(v.want, "%q", quantity);
}

// The status of `c` whose value `state` holds and which does not hold yet.
StudyWords pending(const VariableWording* v, const TutorialCondition& c,
                   const TutorialState& state) {
  if (!v || c.kind == ConditionKind::kBoolean) return {kNotYet.en, kNotYet.zh};
  if (c.kind == ConditionKind::kWord) {
    const auto it = state.words.find(c.variable);
    const WordName* now = it == state.words.end() ? nullptr : findWordName(c.variable, it->second);
    if (!now) return {kNotYet.en, kNotYet.zh};
    return fill(kNow, "%k", {now->name.en, now->name.zh});
  }
  const auto it = state.numbers.find(c.variable);
  if (it == state.numbers.end()) return {kNotYet.en, kNotYet.zh};
  const std::string k = std::to_string(it->second), n = std::to_string(c.number);
  const bool counting = v->counts && (c.op == ConditionOperator::kGreaterEqual ||
                                      c.op == ConditionOperator::kGreater);
  if (counting) return fill(fill(kSoFar, "%k", {k, k}), "%n", {n, n});
  return fill(kNow, "%k", {k + v->unit.en, " " + k + v->unit.zh});
}

}  // namespace

StudyWords tutorialGoalWords(const TutorialCondition& c) {
  const VariableWording* v = findWording(c.variable);
  if (!v) return {kFallback.en, kFallback.zh};
  const bool equal = c.op == ConditionOperator::kEqual;
  switch (c.kind) {
    case ConditionKind::kWord: {
      const WordName* name = findWordName(c.variable, c.word);
      if (!name || (c.op != ConditionOperator::kEqual && c.op != ConditionOperator::kNotEqual))
        return {kFallback.en, kFallback.zh};
      return fill(equal ? v->want : v->other, "%w", {name->name.en, name->name.zh});
    }
    case ConditionKind::kBoolean: {
      if (c.op != ConditionOperator::kEqual && c.op != ConditionOperator::kNotEqual)
        return {kFallback.en, kFallback.zh};
      const bool wants_true = (c.number != 0) == equal;
      const Words& w = wants_true ? v->want : v->other;
      return {w.en, w.zh};
    }
    case ConditionKind::kInteger:
      return integerGoal(*v, c);
  }
  return {kFallback.en, kFallback.zh};
}

StudyWords tutorialCheckWords(const TutorialCondition& c, const TutorialState& state) {
  const StudyWords goal = tutorialGoalWords(c);
  const StudyWords status = conditionHolds(c, state) ? StudyWords{kDone.en, kDone.zh}
                                                     : pending(findWording(c.variable), c, state);
  return {goal.en + " (" + status.en + ")", goal.zh + "（" + status.zh + "）"};
}

StudyWords tutorialStepWords(const std::vector<TutorialCondition>& expect,
                             const TutorialState& state) {
  StudyWords all;
  for (const TutorialCondition& c : expect) {
    const StudyWords one = tutorialCheckWords(c, state);
    all.en += (all.en.empty() ? "" : "; ") + one.en;
    all.zh += (all.zh.empty() ? "" : "；") + one.zh;
  }
  return all;
}

bool tutorialVariableWorded(std::string_view variable) {
  return findWording(variable) != nullptr;
}

std::string tutorialWordsZhText() {
  std::string text;
  for (const WordName& n : kWordNames) text += n.name.zh;
  for (const VariableWording& v : kVariables) {
    text += v.want.zh;
    if (v.other.zh) text += v.other.zh;
    text += v.unit.zh;
  }
  for (const Quantity& q : kQuantities) text += q.words.zh;
  for (const Words& w : {kDone, kNotYet, kSoFar, kNow, kFallback}) text += w.zh;
  return text + "（）；";
}

}  // namespace cb
