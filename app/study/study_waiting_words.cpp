#include "app/study/study_waiting_words.h"

#include <iterator>

namespace cb {
namespace {

struct Wording {
  StudyWaitLine line;
  const char* en;
  const char* zh;
};

// In StudyWaitLine's order. The participant's buttons read English over Chinese
// (app/shell/study/study_page.cpp), so each language names a button by its own line: "Continue"
// is 点“继续”, "OK" 点“确定”, "Skip" 点“跳过”, "I agree" 点“我同意”, "I'm done" 点“我画完了”.
constexpr Wording kWordings[] = {
    {StudyWaitLine::kChoosePause,
     "Operator: choose why to pause (tap a reason or press its number; Esc cancels)",
     "操作员：请选择暂停的原因（点一个原因或按它的数字键；按 Esc 取消）"},
    {StudyWaitLine::kChooseSkip,
     "Operator: choose why to skip (tap a reason or press its number; Esc cancels)",
     "操作员：请选择跳过的原因（点一个原因或按它的数字键；按 Esc 取消）"},
    {StudyWaitLine::kChooseAbort,
     "Operator: choose why to abort (tap a reason or press its number; Esc cancels)",
     "操作员：请选择中止的原因（点一个原因或按它的数字键；按 Esc 取消）"},
    {StudyWaitLine::kPaused,
     "Paused by the operator (%s). Waiting for the operator to resume (Ctrl+Alt+P).",
     "操作员已暂停。请等待操作员继续（Ctrl+Alt+P）。"},
    {StudyWaitLine::kClosing, "Finishing (%s): lift the pen; the work is being saved.",
     "正在结束：请抬起笔，您的作品正在保存。"},
    {StudyWaitLine::kConsent,
     "Waiting for your consent: read the text, then tap \"I agree\" (or press Space), or \"I do "
     "not agree\" to end the session here.",
     "等待您的同意：请阅读上面的文字，然后点“我同意”（或按空格键）；如果不同意，请点“我不同意”，"
     "会话就在这里结束。"},
    {StudyWaitLine::kParticipant,
     "Your participant code is %s. Tap \"Continue\" (or press Space) to begin.",
     "您的参与者编号是 %s。点“继续”或按空格键开始。"},
    {StudyWaitLine::kIntroduction, "Read the introduction, then tap \"Continue\" (or press Space).",
     "请阅读介绍，然后点“继续”或按空格键。"},
    {StudyWaitLine::kTutorial,
     "Step %s of %s: do what the step says; it moves on by itself when it is done.",
     "第 %s 步，共 %s 步：按这一步说的做，做到后会自动进入下一步。"},
    {StudyWaitLine::kPaintTimed, "Paint with the pen. Time left %s.", "用笔画画。剩余时间 %s。"},
    {StudyWaitLine::kPaint, "Paint with the pen.", "用笔画画。"},
    {StudyWaitLine::kTaskTimed, "Paint with the pen. Time left %s. Tap \"I'm done\" when finished.",
     "用笔画画。剩余时间 %s。画完后点“我画完了”。"},
    {StudyWaitLine::kTask, "Paint with the pen. Tap \"I'm done\" when finished.",
     "用笔画画。画完后点“我画完了”。"},
    {StudyWaitLine::kDemographics,
     "Enter your answer with the on-screen keys and tap OK (or Skip to leave it blank).",
     "用屏幕上的键盘输入答案，然后点“确定”；点“跳过”可以不填。"},
    {StudyWaitLine::kQuestionnaire,
     "Tap the box that matches how much you agree (Skip leaves it blank).",
     "点最符合您同意程度的方框；点“跳过”可以不答。"},
    {StudyWaitLine::kFreeText,
     "Type a comment with the on-screen keys and tap OK (Skip if you have none).",
     "用屏幕上的键盘写下您的意见，然后点“确定”；没有意见就点“跳过”。"},
    {StudyWaitLine::kDeclined,
     "You did not agree, so the session has ended. Thank you for your time.",
     "您没有同意参加，会话已结束。感谢您抽出时间。"},
    {StudyWaitLine::kAborted, "The session was stopped by the operator. Thank you.",
     "操作员已停止本次会话。谢谢您。"},
    {StudyWaitLine::kDone, "All done. Thank you for taking part!", "全部完成。感谢您的参与！"},
};
static_assert(std::size(kWordings) == size_t(StudyWaitLine::kCount), "one wording a line");

constexpr bool inOrder() {
  for (size_t i = 0; i < std::size(kWordings); ++i)
    if (size_t(kWordings[i].line) != i) return false;
  return true;
}
static_assert(inOrder(), "kWordings is in StudyWaitLine's order");

std::string filled(const char* wording, const std::vector<std::string>& values) {
  std::string text = wording;
  size_t next = 0;
  for (size_t at = text.find("%s"); at != std::string::npos; at = text.find("%s", at)) {
    const std::string value = next < values.size() ? values[next] : "";
    ++next;
    text.replace(at, 2, value);
    at += value.size();
  }
  return text;
}

}  // namespace

StudyWords studyWaitingWords(StudyWaitLine line, const std::vector<std::string>& values) {
  const Wording& w = kWordings[size_t(line)];
  return {filled(w.en, values), filled(w.zh, values)};
}

std::string studyWaitingZhText() {
  std::string text;
  for (const Wording& w : kWordings) text += w.zh;
  return text;
}

}  // namespace cb
