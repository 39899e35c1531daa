#include "app/shell/study/study_page.h"

#include <algorithm>
#include <cstdio>

#include "app/shell/command_table.h"

namespace cb {
namespace {

const glm::vec4 kBackground{0.09f, 0.11f, 0.15f, 1.0f};
const glm::vec4 kPanel{0.06f, 0.08f, 0.11f, 0.86f};
const glm::vec4 kTargetColour{0.22f, 0.34f, 0.52f, 1.0f};
const glm::vec4 kSelectedColour{0.95f, 0.62f, 0.18f, 1.0f};
const glm::vec4 kQuietColour{0.25f, 0.27f, 0.31f, 1.0f};
const glm::vec4 kVeil{0.0f, 0.0f, 0.0f, 0.72f};
const glm::vec4 kDoneColour{0.18f, 0.55f, 0.3f, 1.0f};

// What the participant taps and reads around it, English over Chinese (the painter's menu's
// languages, app/shell/command_table.h).
const Bilingual kAgreeText{"I agree", "我同意"};
const Bilingual kDeclineText{"I do not agree", "我不同意"};
const Bilingual kDeclinedTitle{"Session ended", "会话已结束"};
const Bilingual kDeclinedBody{
    "You did not agree to take part, so the session ends here: no task was started, and nothing "
    "you would have drawn or answered is recorded. Thank you for your time.",
    "您没有同意参加，本次会话到此结束：没有开始任何任务，也不会记录您的绘画或回答。感谢您抽出时间"
    "。"};
const Bilingual kDoneText{"I'm done", "我画完了"};
const Bilingual kDoneAskText{"Finish this task now?", "现在结束这个任务吗？"};
const Bilingual kDoneYesText{"Yes, I'm done", "是的，画完了"};
const Bilingual kKeepPaintingText{"Keep painting", "继续画"};

class PageBuilder {
 public:
  PageBuilder(StudyPage* page, int w, int h) : page_(*page), w_(float(w)), h_(float(h)) {}

  float w() const { return w_; }
  float h() const { return h_; }
  float title() const { return std::max(18.0f, 0.052f * h_); }
  float body() const { return std::max(14.0f, 0.036f * h_); }
  float small() const { return std::max(12.0f, 0.029f * h_); }

  void fill(glm::vec4 colour) { page_.boxes.push_back(makeHudRect(0, 0, w_, h_, colour)); }
  void box(float x0, float y0, float x1, float y1, glm::vec4 colour) {
    page_.boxes.push_back(makeHudRect(x0, y0, x1, y1, colour));
  }
  void text(float x, float y, const std::string& text, float size, uint32_t rgba = kStudyTextColour,
            float wrap = 0.0f) {
    UiLabel label;
    label.x = x, label.y = y, label.text = text, label.size_px = size, label.rgba = rgba;
    label.wrap_width = wrap;
    page_.labels.push_back(label);
  }
  void centred(float x, float y, const std::string& text, float size,
               uint32_t rgba = kStudyTextColour) {
    UiLabel label;
    label.x = x, label.y = y, label.text = text, label.size_px = size, label.rgba = rgba;
    label.centred = true;
    page_.labels.push_back(label);
  }
  StudyTarget& target(float x0, float y0, float x1, float y1, StudyTargetAction action,
                      const std::string& label, int value = 0, bool selected = false,
                      glm::vec4 colour = kTargetColour) {
    box(x0, y0, x1, y1, selected ? kSelectedColour : colour);
    StudyTarget t;
    t.x0 = x0, t.y0 = y0, t.x1 = x1, t.y1 = y1;
    t.action = action, t.value = value, t.label = label, t.selected = selected;
    page_.targets.push_back(t);
    // One centred line per line of the label (English over Chinese), the block centred.
    std::vector<std::string> lines;
    for (size_t at = 0; at <= label.size();) {
      const size_t end = std::min(label.find('\n', at), label.size());
      lines.push_back(label.substr(at, end - at));
      at = end + 1;
    }
    const float n = float(lines.size());
    const float fill = n > 1.0f ? 0.8f / (1.25f * (n - 1.0f) + 1.2f) : 0.42f;
    const float size = std::min(body(), fill * (y1 - y0));
    float y = 0.5f * (y0 + y1) - 0.5f * (1.25f * (n - 1.0f) + 1.2f) * size;
    for (const std::string& line : lines) {
      centred(0.5f * (x0 + x1), y, line, size);
      y += 1.25f * size;
    }
    return page_.targets.back();
  }
  void setImage(float x0, float y0, float x1, float y1) {
    page_.image[0] = x0, page_.image[1] = y0, page_.image[2] = x1, page_.image[3] = y1;
  }
  // The line at the foot that says what the page waits for.
  void waiting(const std::string& what) {
    box(0, h_ - 1.9f * small(), w_, h_, {0.0f, 0.0f, 0.0f, 0.6f});
    text(0.03f * w_, h_ - 1.55f * small(), what, small(), kStudyHintColour);
  }

 private:
  StudyPage& page_;
  float w_, h_;
};

// The on-screen keyboard's pages (StudyPageInput::keyboard_page): each a 10-key grid of up to
// four rows; a key types its text. Symbols reach beyond ASCII (the Latin-1 page of the atlas and
// typographic marks); the protocol's page holds its language's characters and words.
const char* const kLowerRows[] = {"1234567890", "qwertyuiop", "asdfghjkl-", "zxcvbnm,.'"};
const char* const kUpperRows[] = {"1234567890", "QWERTYUIOP", "ASDFGHJKL-", "ZXCVBNM,.'"};
const std::vector<std::string> kSymbolKeys = {
    "!",      "?",      "@",      "#",      "&",      "*",      "(",      ")",
    "+",      "=",      ":",      ";",      "\"",     "/",      "%",      "<",
    ">",      "[",      "]",      "_",      "\u20ac", "\u00a3", "\u00a5", "\u00b0",
    "\u00b7", "\u2026", "$",      "\u00ab", "\u00bb", "~",      "\u00e4", "\u00f6",
    "\u00fc", "\u00e9", "\u00e8", "\u00e0", "\u00e7", "\u00df", "\u00f1", "\u00f8"};

std::vector<std::string> keyboardKeys(const StudyKeyboardPage& own, int page, bool digits_only) {
  std::vector<std::string> keys;
  if (page == kKeyboardSymbols && !digits_only) return kSymbolKeys;
  if (page == kKeyboardProtocol && !digits_only && !own.keys.empty()) return own.keys;
  const char* const* rows = page == kKeyboardUpper ? kUpperRows : kLowerRows;
  for (int r = 0; r < (digits_only ? 1 : 4); ++r)
    for (int i = 0; rows[r][i]; ++i) keys.emplace_back(1, rows[r][i]);
  return keys;
}

void keyboard(PageBuilder& b, const StudyPageInput& input, const StudyKeyboardPage& own, float top,
              bool digits_only) {
  // An on-screen keyboard for the pen: a page of keys, then the page keys (Shift, symbols, the
  // protocol's language), Space, delete, Skip and OK. Keys are ~7% of the width (about 37 mm on
  // a 24" screen).
  const float key_w = 0.07f * b.w(), key_h = 0.075f * b.h(), gap = 0.008f * b.w();
  const float row_w = 10 * key_w + 9 * gap;
  const float left = 0.5f * (b.w() - row_w);
  // The text typed so far, in a field above the keys.
  b.box(left, top, left + row_w, top + 1.6f * b.body(), {0.95f, 0.95f, 0.95f, 1.0f});
  b.text(left + 0.4f * b.body(), top + 0.25f * b.body(), input.typed + "_", b.body(), 0x101010ffu);
  float y = top + 1.6f * b.body() + 2 * gap;
  const std::vector<std::string> keys = keyboardKeys(own, input.keyboard_page, digits_only);
  for (size_t k = 0; k < keys.size(); ++k) {
    const float x = left + float(k % 10) * (key_w + gap);
    StudyTarget& t = b.target(x, y, x + key_w, y + key_h, StudyTargetAction::kKey, keys[k]);
    t.text = keys[k];
    if (k % 10 == 9 || k + 1 == keys.size()) y += key_h + gap;
  }
  // Every page keeps its four rows' height, so the bottom row stays where the pen expects it.
  y = top + 1.6f * b.body() + 2 * gap + float(digits_only ? 1 : 4) * (key_h + gap);
  float x = left;
  const auto key = [&](float width_keys, StudyTargetAction action, const std::string& label,
                       int value, bool selected, glm::vec4 colour) -> StudyTarget& {
    const float x1 = x + width_keys * key_w + (width_keys - 1) * gap;
    StudyTarget& t = b.target(x, y, x1, y + key_h, action, label, value, selected, colour);
    x = x1 + gap;
    return t;
  };
  if (!digits_only) {
    const int page = input.keyboard_page;
    key(1, StudyTargetAction::kKeyboardPage, "Shift", kKeyboardUpper, page == kKeyboardUpper,
        kTargetColour);
    key(1, StudyTargetAction::kKeyboardPage, "#+=", kKeyboardSymbols, page == kKeyboardSymbols,
        kTargetColour);
    if (!own.keys.empty())
      key(1, StudyTargetAction::kKeyboardPage, own.label, kKeyboardProtocol,
          page == kKeyboardProtocol, kTargetColour);
    key(own.keys.empty() ? 3 : 2, StudyTargetAction::kKey, "space", 0, false, kTargetColour).text =
        " ";
  }
  key(digits_only ? 2 : 1.5f, StudyTargetAction::kBackspace, "delete", 0, false, kTargetColour);
  key(digits_only ? 2 : 1.5f, StudyTargetAction::kSkipField, "Skip", 0, false, kQuietColour);
  b.target(x, y, left + row_w, y + key_h, StudyTargetAction::kOk, "OK", 0, false,
           {0.18f, 0.55f, 0.3f, 1.0f});
}

// The form pages' frame: margins, text width and the button row.
struct FormLayout {
  float margin, wrap, button_w, button_h, button_y;
};

// A form page's heading at y; returns the y below it.
float formHeading(PageBuilder& b, const FormLayout& l, float y, const std::string& text) {
  b.text(l.margin, y, text, b.title());
  return y + 1.6f * b.title();
}

// A demographic field: its label, then its choices in a row or the keyboard.
void demographicsForm(PageBuilder& b, const StudyRunState& state, const StudyPageInput& input,
                      const FormLayout& l, float y) {
  const StudyProtocol& p = state.protocol();
  const DemographicField& f = p.demographics[size_t(state.fieldIndex())];
  y = formHeading(b, l, y,
                  "About you (" + std::to_string(state.fieldIndex() + 1) + " of " +
                      std::to_string(p.demographics.size()) + ")");
  b.text(l.margin, y, f.label, b.body(), kStudyTextColour, l.wrap);
  y += 2.2f * b.body();
  if (!input.message.empty())
    b.text(l.margin, y - 0.9f * b.body(), input.message, b.small(), kStudyHintColour, l.wrap);
  if (f.kind == DemographicField::Kind::kChoice) {
    const float cw = std::min(0.25f * b.w(), l.wrap / float(std::max<size_t>(1, f.choices.size())));
    for (size_t i = 0; i < f.choices.size(); ++i) {
      const float x = l.margin + float(i) * cw;
      StudyTarget& t =
          b.target(x + 4, y, x + cw - 4, y + l.button_h, StudyTargetAction::kChoice, f.choices[i]);
      t.text = f.choices[i];
    }
    b.target(l.margin, y + 1.4f * l.button_h, l.margin + l.button_w, y + 2.4f * l.button_h,
             StudyTargetAction::kSkipField, "Skip", 0, false, kQuietColour);
  } else {
    keyboard(b, input, p.keyboard, y, f.kind == DemographicField::Kind::kInteger);
  }
}

// A questionnaire item: its text, the scale as big boxes with their words, Back and Skip.
void questionnaireForm(PageBuilder& b, const StudyRunState& state, const FormLayout& l, float y) {
  const StudyProtocol& p = state.protocol();
  const int i = state.itemIndex();
  const QuestionnaireItem& item = p.items[size_t(i)];
  y = formHeading(b, l, y,
                  "Questionnaire: item " + std::to_string(i + 1) + " of " +
                      std::to_string(p.items.size()) +
                      (item.section.empty() ? std::string() : " (" + item.section + ")"));
  // The thesis's *emphasis* marks are the protocol's transcription, not for the participant.
  std::string text = item.text + (item.text_zh.empty() ? "" : "\n" + item.text_zh);
  text.erase(std::remove(text.begin(), text.end(), '*'), text.end());
  b.text(l.margin, y, text, 1.15f * b.body(), kStudyTextColour, l.wrap);
  // Five (n) big boxes in a row, the scale's words under each number.
  const int n = int(p.scale_labels.size());
  const float gap = 0.012f * b.w();
  const float bw = (l.wrap - float(n - 1) * gap) / float(n), bh = 0.16f * b.h();
  const float by = 0.45f * b.h();
  const std::optional<int> given = state.itemAnswers()[size_t(i)];
  for (int k = 1; k <= n; ++k) {
    const float x = l.margin + float(k - 1) * (bw + gap);
    b.target(x, by, x + bw, by + bh, StudyTargetAction::kAnswer, std::to_string(k), k,
             given && *given == k);
    b.centred(x + 0.5f * bw, by + bh + 0.3f * b.small(), p.scale_labels[size_t(k - 1)], b.small());
    if (size_t(k) <= p.scale_labels_zh.size())
      b.centred(x + 0.5f * bw, by + bh + 1.55f * b.small(), p.scale_labels_zh[size_t(k - 1)],
                b.small());
  }
  const float ry = by + bh + (p.scale_labels_zh.empty() ? 2.2f : 3.4f) * b.small();
  if (i > 0)
    b.target(l.margin, ry, l.margin + l.button_w, ry + 0.7f * l.button_h,
             StudyTargetAction::kBackItem, "Back", 0, false, kQuietColour);
  b.target(b.w() - l.margin - l.button_w, ry, b.w() - l.margin, ry + 0.7f * l.button_h,
           StudyTargetAction::kSkipItem, "Skip", 0, false, kQuietColour);
}

void formPage(PageBuilder& b, const StudyRunState& state, const StudyPageInput& input) {
  const StudyProtocol& p = state.protocol();
  const float margin = 0.06f * b.w();
  const float wrap = b.w() - 2 * margin;
  const float button_w = 0.22f * b.w(), button_h = 0.1f * b.h();
  const float button_y = b.h() - 2.2f * b.small() - button_h - 0.03f * b.h();
  b.fill(kBackground);
  float y = 0.05f * b.h();
  const auto heading = [&](const std::string& text) {
    b.text(margin, y, text, b.title());
    y += 1.6f * b.title();
  };
  switch (state.stage()) {
    case StudyStageKind::kConsent: {
      heading("Consent");
      b.text(margin, y, p.consent, b.body(), kStudyTextColour, wrap);
      // Agree and decline side by side, the same size: declining is as easy as agreeing.
      const float gap = 0.04f * b.w();
      b.target(0.5f * (b.w() - gap) - button_w, button_y, 0.5f * (b.w() - gap), button_y + button_h,
               StudyTargetAction::kAgree, kAgreeText.twoLines());
      b.target(0.5f * (b.w() + gap), button_y, 0.5f * (b.w() + gap) + button_w, button_y + button_h,
               StudyTargetAction::kDecline, kDeclineText.twoLines(), 0, false, kQuietColour);
      break;
    }
    case StudyStageKind::kParticipant:
      heading("Your participant code");
      b.centred(0.5f * b.w(), 0.3f * b.h(), state.participantId(), 2.4f * b.title(),
                kStudyHintColour);
      b.text(margin, 0.55f * b.h(),
             "Everything recorded today is filed under this code, never under your name.", b.body(),
             kStudyTextColour, wrap);
      b.target(0.5f * b.w() - button_w * 0.5f, button_y, 0.5f * b.w() + button_w * 0.5f,
               button_y + button_h, StudyTargetAction::kContinue, "Continue");
      break;
    case StudyStageKind::kIntroduction: {
      heading("Introduction");
      std::string text = p.introduction.text;
      if (!p.introduction.video.empty())
        text += "\n(The operator plays the video " + p.introduction.video + ".)";
      b.text(margin, y, text, b.body(), kStudyTextColour, wrap);
      b.target(0.5f * b.w() - button_w * 0.5f, button_y, 0.5f * b.w() + button_w * 0.5f,
               button_y + button_h, StudyTargetAction::kContinue, "Continue");
      break;
    }
    case StudyStageKind::kDemographics:
      demographicsForm(b, state, input, {margin, wrap, button_w, button_h, button_y}, y);
      break;
    case StudyStageKind::kQuestionnaire:
      questionnaireForm(b, state, {margin, wrap, button_w, button_h, button_y}, y);
      break;
    case StudyStageKind::kFreeText: {
      const FreeTextQuestion& q = p.free_text[size_t(state.freeTextIndex())];
      heading("Comments (" + std::to_string(state.freeTextIndex() + 1) + " of " +
              std::to_string(p.free_text.size()) + ", optional)");
      b.text(margin, y, q.prompt, b.body(), kStudyTextColour, wrap);
      keyboard(b, input, p.keyboard, y + 2.4f * b.body(), false);
      break;
    }
    case StudyStageKind::kDone:
      if (state.declined()) {
        heading(kDeclinedTitle.oneLine());
        b.text(margin, y, std::string(kDeclinedBody.en) + "\n\n" + kDeclinedBody.zh, b.body(),
               kStudyTextColour, wrap);
        break;
      }
      heading(state.aborted() ? "Session stopped" : "Thank you");
      b.text(margin, y,
             state.aborted() ? "The operator stopped the session (" + state.abortReason() +
                                   "). What was recorded so far is kept."
                             : "Your answers and clouds are saved under " + state.participantId() +
                                   ". Please tell the operator you have finished.",
             b.body(), kStudyTextColour, wrap);
      break;
    default:
      break;
  }
}

float countdownSize(const PageBuilder& b) {
  return 1.5f * b.title();
}
float countdownTop(const PageBuilder& b) {
  return b.h() - 2.2f * b.small() - 1.4f * countdownSize(b);
}

// The task's "I'm done": one target; tapped, a question with "Yes, I'm done" and "Keep
// painting" in its place (a stray tap near the canvas's edge does not end a task).
void doneTargets(PageBuilder& b, float x0, float x1, bool asked) {
  const float h = 0.085f * b.h(), gap = 0.01f * b.w();
  // Just above the countdown, where the task's time is read.
  float y = countdownTop(b) - 0.02f * b.h() - h - (asked ? 2.7f * b.small() : 0.0f);
  if (!asked) {
    b.target(x0, y, x1, y + h, StudyTargetAction::kDone, kDoneText.twoLines(), 0, false,
             kDoneColour);
    return;
  }
  b.text(x0, y, kDoneAskText.twoLines(), b.small(), kStudyHintColour);
  y += 2.7f * b.small();
  const float mid = 0.5f * (x0 + x1);
  b.target(x0, y, mid - 0.5f * gap, y + h, StudyTargetAction::kDoneConfirm, kDoneYesText.twoLines(),
           0, false, kDoneColour);
  b.target(mid + 0.5f * gap, y, x1, y + h, StudyTargetAction::kDoneCancel,
           kKeepPaintingText.twoLines(), 0, false, kQuietColour);
}

void paintingPanel(PageBuilder& b, const StudyRunState& state, const StudyPageInput& input) {
  // A column at the right: what this stage is, the reference image, the instruction and its
  // live check, the countdown. The painter's status line stays visible along the top.
  const StudyProtocol& p = state.protocol();
  const float x0 = 0.72f * b.w(), top = 0.075f * b.h(), pad = 0.012f * b.w();
  const float wrap = b.w() - x0 - 2 * pad;
  b.box(x0, top, b.w(), b.h(), kPanel);
  float y = top + pad;
  const auto line = [&](const std::string& text, float size, uint32_t colour, float advance) {
    b.text(x0 + pad, y, text, size, colour, wrap);
    y += advance * size;
  };
  const double left = state.secondsLeft(input.now_ns);
  switch (state.stage()) {
    case StudyStageKind::kTutorial: {
      const TutorialStep& step = p.tutorial[size_t(state.tutorialStep())];
      line("Tutorial: step " + std::to_string(state.tutorialStep() + 1) + " of " +
               std::to_string(p.tutorial.size()),
           b.body(), kStudyTextColour, 1.6f);
      line(step.instruction, 1.1f * b.body(), kStudyTextColour, 4.2f);
      line("Done when: " + input.check_status, b.small(), kStudyHintColour, 3.2f);
      // The tutorial has a planned length (§7.5: ten minutes), not a limit: it ends when its
      // steps are done (or skipped by the operator).
      const int elapsed = int(state.stageSeconds(input.now_ns));
      char text[96];
      std::snprintf(text, sizeof text, "Tutorial time %d:%02d (planned %.0f min)", elapsed / 60,
                    elapsed % 60, p.tutorial_minutes);
      line(text, b.small(), kStudyTextColour, 1.5f);
      break;
    }
    case StudyStageKind::kFreeDrawing:
      line("Free drawing", b.body(), kStudyTextColour, 1.6f);
      line(p.free_drawing.text, b.small(), kStudyTextColour, 6.0f);
      break;
    case StudyStageKind::kTask: {
      const StudyTask* task = state.task();
      line("Task " + std::to_string(state.position().order + 1) + " of " +
               std::to_string(state.taskCount()) + ": " + task->title,
           b.body(), kStudyTextColour, 2.4f);
      if (input.image_aspect > 0.0f) {
        const float iw = wrap, ih = std::min(iw / input.image_aspect, 0.4f * b.h());
        const float w = ih * input.image_aspect;
        b.setImage(x0 + pad, y, x0 + pad + w, y + ih);
        y += ih + pad;
      }
      line("Paint a cloud like the picture.", b.small(), kStudyTextColour, 1.5f);
      doneTargets(b, x0 + pad, b.w() - pad, input.done_asked);
      break;
    }
    default:
      break;
  }
  if (left >= 0) {
    char text[64];
    std::snprintf(text, sizeof text, "Time left %d:%02d", int(left) / 60, int(left) % 60);
    b.text(x0 + pad, countdownTop(b), text, countdownSize(b),
           left < 60 ? 0xff8060ffu : kStudyTextColour);
  }
}

void operatorChooser(PageBuilder& b, const StudyRunState& state) {
  b.box(0, 0, b.w(), b.h(), kVeil);
  const OperatorAction action = state.choosingFor();
  const std::vector<std::string>& reasons = operatorReasons(action);
  const float x0 = 0.25f * b.w(), x1 = 0.75f * b.w();
  float y = 0.12f * b.h();
  b.centred(0.5f * b.w(), y,
            std::string("Operator: why ") +
                (action == OperatorAction::kPause ? "pause?"
                 : action == OperatorAction::kSkip
                     ? (state.stage() == StudyStageKind::kTutorial ? "skip this step?"
                                                                   : "skip this stage?")
                     : "abort the session?"),
            b.title());
  y += 1.8f * b.title();
  const float bh = 0.085f * b.h(), gap = 0.012f * b.h();
  for (size_t i = 0; i < reasons.size(); ++i) {
    b.target(x0, y, x1, y + bh, StudyTargetAction::kReason,
             std::to_string(i + 1) + "  " + reasons[i], int(i));
    y += bh + gap;
  }
  b.target(x0, y + gap, x0 + 0.4f * (x1 - x0), y + gap + bh, StudyTargetAction::kCancel,
           "Cancel (Esc)", 0, false, kQuietColour);
}

}  // namespace

std::string studyPageText(const StudyProtocol& p) {
  std::string text;
  for (const Bilingual& b : {kAgreeText, kDeclineText, kDeclinedTitle, kDeclinedBody, kDoneText,
                             kDoneAskText, kDoneYesText, kKeepPaintingText})
    text += b.zh;
  text += p.consent + p.introduction.text + p.free_drawing.text;
  for (const TutorialStep& s : p.tutorial) text += s.instruction;
  for (const StudyTask& t : p.tasks) text += t.title;
  for (const DemographicField& f : p.demographics) {
    text += f.label;
    for (const std::string& c : f.choices) text += c;
  }
  for (const QuestionnaireItem& item : p.items) text += item.text + item.text_zh;
  for (const std::string& label : p.scale_labels_zh) text += label;
  for (const FreeTextQuestion& q : p.free_text) text += q.prompt;
  text += p.keyboard.label;
  for (const std::string& key : p.keyboard.keys) text += key;
  for (const std::string& key : kSymbolKeys) text += key;
  return text;
}

const StudyTarget* StudyPage::find(StudyTargetAction action, int value) const {
  for (const StudyTarget& t : targets)
    if (t.action == action && (value < 0 || t.value == value)) return &t;
  return nullptr;
}

const StudyTarget* StudyPage::hit(float x, float y) const {
  // Later targets are on top (the operator's chooser over the page).
  for (auto it = targets.rbegin(); it != targets.rend(); ++it)
    if (it->contains(x, y)) return &*it;
  return nullptr;
}

StudyPage buildStudyPage(const StudyRunState& state, const StudyPageInput& input, int width,
                         int height) {
  StudyPage page;
  PageBuilder b(&page, width, height);
  if (isPaintingStage(state.stage())) {
    if (!input.painter_menu_open) paintingPanel(b, state, input);
  } else {
    formPage(b, state, input);
  }
  if (state.choosing() || state.paused()) {
    // The page stays visible, veiled, without its words, picture or targets: only the
    // chooser takes taps.
    page.targets.clear();
    page.labels.clear();
    std::fill(page.image, page.image + 4, 0.0f);
  }
  if (state.choosing()) {
    operatorChooser(b, state);
  } else if (state.paused()) {
    b.box(0, 0, b.w(), b.h(), kVeil);
    b.centred(0.5f * b.w(), 0.33f * b.h(), "Paused", 2.0f * b.title());
    b.centred(0.5f * b.w(), 0.33f * b.h() + 3.0f * b.title(),
              "by the operator: " + state.pauseReason(), b.body());
    b.centred(0.5f * b.w(), 0.33f * b.h() + 3.0f * b.title() + 1.8f * b.body(),
              "The session goes on when the operator resumes (Ctrl+Alt+P).", b.body());
  }
  b.waiting(state.waitingFor(input.now_ns));
  if (!input.storage_warning.empty()) {
    // The operator's warning over every page: a red band along the top edge (over the
    // painter's status line; the participant's hints stay at the bottom).
    const float band = 3.4f * b.small();
    b.box(0, 0, b.w(), band, {0.62f, 0.08f, 0.06f, 1.0f});
    b.text(0.02f * b.w(), 0.4f * b.small(), input.storage_warning, b.small(), 0xffffffffu,
           0.96f * b.w());
  }
  return page;
}

}  // namespace cb
