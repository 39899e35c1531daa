#include "app/shell/study/study_page.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <memory>

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
const uint32_t kSavedColour =
    0x8ee6a6ffu;  // a saved task's words: the green of "I'm done", lighter

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
const Bilingual kTaskHowText{
    "Paint a cloud like the picture. It is saved for you when you tap \"I'm done\" or when the "
    "time is up.",
    "照着图片画一朵云。点“我画完了”或时间到时，它会为您保存。"};
const Bilingual kDoneAskText{"Finish this task now?", "现在结束这个任务吗？"};
const Bilingual kDoneYesText{"Yes, I'm done", "是的，画完了"};
const Bilingual kKeepPaintingText{"Keep painting", "继续画"};
// A painting stage that ended (time up, "I'm done", the operator) and waits for the stroke under
// the pen to end before it saves: in place of "I'm done".
const Bilingual kTimeUpText{"Time is up. Lift the pen: your cloud is being saved.",
                            "时间到了。请抬起笔：您的云正在保存。"};
// The task that just ended, on the next page (%d: its number in the participant's order).
const Bilingual kTaskSavedText{"Task %d saved.", "任务 %d 已保存。"};
const Bilingual kTaskKeptText{"Task %d is kept and being saved.", "任务 %d 已保留，正在保存。"};
// The countdown (%s: "M:SS"): English, big, over its Chinese.
const Bilingual kTimeLeftText{"Time left %s", "剩余时间 %s"};
const Bilingual kFinishingText{"This task is ending. Lift the pen: your cloud is being saved.",
                               "这个任务即将结束。请抬起笔：您的云正在保存。"};
// The form pages' buttons and the on-screen keyboard's named keys.
const Bilingual kContinueText{"Continue", "继续"};
const Bilingual kOkText{"OK", "确定"};
const Bilingual kSkipText{"Skip", "跳过"};
const Bilingual kBackText{"Back", "返回"};
const Bilingual kDeleteText{"delete", "删除"};
const Bilingual kSpaceText{"space", "空格"};
// The form pages' headings (%d: an item's number, the number of items).
const Bilingual kConsentTitle{"Consent", "知情同意"};
const Bilingual kParticipantTitle{"Your participant code", "您的参与者编号"};
const Bilingual kParticipantBody{
    "Everything recorded today is filed under this code, never under your name.",
    "今天记录的一切都只按这个编号保存，不会用您的名字。"};
const Bilingual kIntroductionTitle{"Introduction", "介绍"};
const Bilingual kAboutYouTitle{"About you (%d of %d)", "关于您（第 %d 项，共 %d 项）"};
const Bilingual kQuestionnaireTitle{"Questionnaire: item %d of %d", "问卷：第 %d 题，共 %d 题"};
const Bilingual kCommentsTitle{"Comments (%d of %d, optional)",
                               "意见（第 %d 条，共 %d 条，可不填）"};
const Bilingual kThanksTitle{"Thank you", "谢谢您"};
const Bilingual kStoppedTitle{"Session stopped", "会话已停止"};
// The closing page's words (%s: the participant code; the operator's reason, English only).
const Bilingual kThanksBody{
    "Your answers and clouds are saved under %s. Please tell the operator you have finished.",
    "您的回答和云已保存在编号 %s 下。请告诉操作员您已完成。"};
const Bilingual kStoppedBody{
    "The operator stopped the session (%s). What was recorded so far is "
    "kept.",
    "操作员停止了本次会话。到目前为止记录的内容都会保留。"};
const Bilingual kFreeDrawingTitle{"Free drawing", "自由绘画"};
// The panel beside the painter: the tutorial's step, its check and its clock (%d:%02d: minutes
// and seconds; %.0f: the planned minutes), the task's place in the participant's order.
const Bilingual kTutorialStepText{"Tutorial: step %d of %d", "教程：第 %d 步，共 %d 步"};
const Bilingual kToFinishText{"To finish this step", "完成这一步"};
const Bilingual kTutorialTimeText{"Tutorial time %d:%02d (planned %.0f min)",
                                  "教程用时 %d:%02d（计划 %.0f 分钟）"};
const Bilingual kTaskOrderText{"Task %d of %d", "第 %d 个任务，共 %d 个"};
// The pause veil (the reason is the operator's, in English).
const Bilingual kPausedTitle{"Paused", "已暂停"};
const Bilingual kPausedBy{"by the operator: ", "操作员暂停了会话。"};
const Bilingual kPausedHow{"The session goes on when the operator resumes (Ctrl+Alt+P).",
                           "操作员恢复后（Ctrl+Alt+P），会话就会继续。"};

// `words` with two numbers in place of its %d: English over Chinese on two lines.
std::string numbered(const Bilingual& words, int a, int b) {
  char en[128], zh[128];
  std::snprintf(en, sizeof en, words.en, a, b);
  std::snprintf(zh, sizeof zh, words.zh, a, b);
  return std::string(en) + "\n" + zh;
}

class PageBuilder {
 public:
  PageBuilder(StudyPage* page, const StudyPageInput& input, int w, int h)
      : page_(*page), w_(float(w)), h_(float(h)), measure_(input.measure) {
    if (!measure_) measure_ = studyTextEstimate;
  }

  float w() const { return w_; }
  float h() const { return h_; }
  float title() const { return std::max(18.0f, 0.052f * h_); }
  float body() const { return std::max(14.0f, 0.036f * h_); }
  float small() const { return std::max(12.0f, 0.029f * h_); }
  // The page's own room: below the operator's band, above the foot line.
  float top() const { return top_; }
  float foot() const { return foot_; }

  // The band's text (may be "") and the foot line's: their heights set top() and foot().
  void frame(const std::string& band_text, const std::string& foot_text) {
    band_text_ = band_text, foot_text_ = foot_text;
    top_ = band_text.empty() ? 0.0f : size(band_text, small(), 0.96f * w_)[1] + 0.8f * small();
    foot_ = h_ - size(foot_text, small(), 0.94f * w_)[1] - 0.7f * small();
  }
  // Draws the foot line and the band (last, over the page).
  void drawFrame() {
    box(0, foot_, w_, h_, {0.0f, 0.0f, 0.0f, 0.6f});
    text(0.03f * w_, foot_ + 0.35f * small(), foot_text_, small(), kStudyHintColour, 0.94f * w_);
    page_.foot[0] = 0, page_.foot[1] = foot_, page_.foot[2] = w_, page_.foot[3] = h_;
    if (band_text_.empty()) return;
    // The operator's warning over every page: a red band along the top edge (over the
    // painter's status line; the participant's hints stay at the foot).
    box(0, 0, w_, top_, {0.62f, 0.08f, 0.06f, 1.0f});
    text(0.02f * w_, 0.4f * small(), band_text_, small(), 0xffffffffu, 0.96f * w_);
    page_.band[2] = w_, page_.band[3] = top_;
  }

  // Width and height of `text` at `size_px`, wrapped at `wrap` (0: not wrapped).
  std::array<float, 2> size(const std::string& text, float size_px, float wrap) const {
    UiLabel label;
    label.text = text, label.size_px = size_px, label.wrap_width = wrap;
    float r[4];
    measure_(label, r);
    return {r[2] - r[0], r[3] - r[1]};
  }
  // The largest size <= `size_px` (down to 60% of it, never under 11 px) at which `text`,
  // wrapped at `wrap`, is at most `max_h` tall and, unwrapped, `max_w` wide (0: any).
  float fit(const std::string& text, float size_px, float wrap, float max_h,
            float max_w = 0) const {
    const float floor = std::max(11.0f, 0.6f * size_px);
    for (float s = size_px;; s *= 0.94f) {
      const std::array<float, 2> d = size(text, s, wrap);
      if ((d[1] <= max_h && (max_w <= 0 || d[0] <= max_w)) || s * 0.94f < floor) return s;
    }
  }

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
  // A wrapped block at (x, y) that ends above `bottom` (smaller when long); returns its foot.
  float block(float x, float y, const std::string& words, float size, float wrap, float bottom,
              uint32_t rgba = kStudyTextColour) {
    const float s = fit(words, size, wrap, bottom - y);
    text(x, y, words, s, rgba, wrap);
    return y + size_of(words, s, wrap);
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
    // One centred line per line of the label (English over Chinese), the block centred and
    // narrower than the target.
    std::vector<std::string> lines;
    for (size_t at = 0; at <= label.size();) {
      const size_t end = std::min(label.find('\n', at), label.size());
      lines.push_back(label.substr(at, end - at));
      at = end + 1;
    }
    const float n = float(lines.size());
    const float fill = n > 1.0f ? 0.8f / (1.25f * (n - 1.0f) + 1.2f) : 0.42f;
    float size = std::min(body(), fill * (y1 - y0));
    for (const std::string& line : lines) size = fit(line, size, 0.0f, y1 - y0, 0.9f * (x1 - x0));
    float y = 0.5f * (y0 + y1) - 0.5f * (1.25f * (n - 1.0f) + 1.0f) * size;
    for (const std::string& line : lines) {
      centred(0.5f * (x0 + x1), y, line, size);
      y += 1.25f * size;
    }
    return page_.targets.back();
  }
  void setImage(float x0, float y0, float x1, float y1) {
    page_.image[0] = x0, page_.image[1] = y0, page_.image[2] = x1, page_.image[3] = y1;
  }

 private:
  float size_of(const std::string& words, float s, float wrap) const {
    return size(words, s, wrap)[1];
  }
  StudyPage& page_;
  float w_, h_;
  StudyTextMeasure measure_;
  std::string band_text_, foot_text_;
  float top_ = 0.0f, foot_ = 0.0f;
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
  const float key_w = 0.07f * b.w(), gap = 0.008f * b.w();
  const float row_w = 10 * key_w + 9 * gap;
  // Keys ~7.5% of the height, lower when the page's text left less room above the foot line.
  const int rows = (digits_only ? 1 : 4) + 1;
  const float room = b.foot() - 0.015f * b.h() - top - 1.6f * b.body() - 2 * gap;
  const float key_h = std::min(0.075f * b.h(), room / float(rows) - gap);
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
    key(own.keys.empty() ? 3 : 2, StudyTargetAction::kKey, kSpaceText.twoLines(), 0, false,
        kTargetColour)
        .text = " ";
  }
  key(digits_only ? 2 : 1.5f, StudyTargetAction::kBackspace, kDeleteText.twoLines(), 0, false,
      kTargetColour);
  key(digits_only ? 2 : 1.5f, StudyTargetAction::kSkipField, kSkipText.twoLines(), 0, false,
      kQuietColour);
  b.target(x, y, left + row_w, y + key_h, StudyTargetAction::kOk, kOkText.twoLines(), 0, false,
           {0.18f, 0.55f, 0.3f, 1.0f});
}

// The form pages' frame: margins, text width and the button row.
struct FormLayout {
  float margin, wrap, button_w, button_h, button_y;
};

// A form page's heading at y: its English, its Chinese under it (smaller); returns the y below.
float formHeading(PageBuilder& b, const FormLayout& l, float y, const std::string& en,
                  const std::string& zh) {
  const float size = b.fit(en, b.title(), 0.0f, 2.0f * b.title(), l.wrap);
  b.text(l.margin, y, en, size);
  y += 1.25f * size;
  const float zh_size = b.fit(zh, b.body(), 0.0f, 2.0f * b.body(), l.wrap);
  b.text(l.margin, y, zh, zh_size);
  return y + 1.2f * zh_size + 0.3f * size;
}
// A heading from `words` (two lines: English, then Chinese), as numbered() gives.
float formHeading(PageBuilder& b, const FormLayout& l, float y, const std::string& words) {
  const size_t at = words.find('\n');
  return formHeading(b, l, y, words.substr(0, at),
                     at == std::string::npos ? "" : words.substr(at + 1));
}

// A demographic field: its label, a refused answer's message, then its choices in a row or the
// keyboard.
void demographicsForm(PageBuilder& b, const StudyRunState& state, const StudyPageInput& input,
                      const FormLayout& l, float y) {
  const StudyProtocol& p = state.protocol();
  const DemographicField& f = p.demographics[size_t(state.fieldIndex())];
  y = formHeading(b, l, y,
                  numbered(kAboutYouTitle, state.fieldIndex() + 1, int(p.demographics.size())));
  y = b.block(l.margin, y, f.label, b.body(), l.wrap, y + 3.0f * b.body()) + 0.4f * b.body();
  if (!input.message.empty())
    y = b.block(l.margin, y, input.message, b.small(), l.wrap, y + 2.2f * b.small(),
                kStudyHintColour);
  y += 0.6f * b.body();
  if (f.kind == DemographicField::Kind::kChoice) {
    const float cw = std::min(0.25f * b.w(), l.wrap / float(std::max<size_t>(1, f.choices.size())));
    const float bh = std::min(l.button_h, (b.foot() - 0.02f * b.h() - y) / 2.4f);
    for (size_t i = 0; i < f.choices.size(); ++i) {
      const float x = l.margin + float(i) * cw;
      StudyTarget& t =
          b.target(x + 4, y, x + cw - 4, y + bh, StudyTargetAction::kChoice, f.choices[i]);
      t.text = f.choices[i];
    }
    b.target(l.margin, y + 1.4f * bh, l.margin + l.button_w, y + 2.4f * bh,
             StudyTargetAction::kSkipField, kSkipText.twoLines(), 0, false, kQuietColour);
  } else {
    keyboard(b, input, p.keyboard, y, f.kind == DemographicField::Kind::kInteger);
  }
}

// A questionnaire item: its text, the scale as big boxes with their words, Back and Skip.
void questionnaireForm(PageBuilder& b, const StudyRunState& state, const FormLayout& l, float y) {
  const StudyProtocol& p = state.protocol();
  const int i = state.itemIndex();
  const QuestionnaireItem& item = p.items[size_t(i)];
  const std::string heading = numbered(kQuestionnaireTitle, i + 1, int(p.items.size()));
  const size_t zh = heading.find('\n');
  y = formHeading(
      b, l, y,
      heading.substr(0, zh) + (item.section.empty() ? std::string() : " (" + item.section + ")"),
      heading.substr(zh + 1));
  // Under the item: the boxes (16% of the height, less when the room is short), the scale's
  // words under them, then Back and Skip; the item's text takes what is left above.
  const int n = int(p.scale_labels.size());
  const float words_h = (p.scale_labels_zh.empty() ? 1.5f : 2.8f) * b.small();
  const float row_h = 0.7f * l.button_h, gap = 0.02f * b.h();
  const float bh = std::clamp(b.foot() - gap - row_h - words_h - 2 * gap - (y + 2.5f * b.body()),
                              0.07f * b.h(), 0.16f * b.h());
  const float below = bh + gap + words_h + gap + row_h + gap;
  // The thesis's *emphasis* marks are the protocol's transcription, not for the participant.
  std::string text = item.text + (item.text_zh.empty() ? "" : "\n" + item.text_zh);
  text.erase(std::remove(text.begin(), text.end(), '*'), text.end());
  const float text_end = b.block(l.margin, y, text, 1.15f * b.body(), l.wrap, b.foot() - below);
  // Five (n) big boxes in a row, the scale's words under each number.
  const float box_gap = 0.012f * b.w();
  const float bw = (l.wrap - float(n - 1) * box_gap) / float(n);
  const float by = std::min(std::max(0.45f * b.h(), text_end + gap), b.foot() - below + gap);
  const std::optional<int> given = state.itemAnswers()[size_t(i)];
  for (int k = 1; k <= n; ++k) {
    const float x = l.margin + float(k - 1) * (bw + box_gap);
    b.target(x, by, x + bw, by + bh, StudyTargetAction::kAnswer, std::to_string(k), k,
             given && *given == k);
    const std::string& en = p.scale_labels[size_t(k - 1)];
    b.centred(x + 0.5f * bw, by + bh + 0.3f * b.small(), en,
              b.fit(en, b.small(), 0.0f, b.small(), 0.96f * bw));
    if (size_t(k) <= p.scale_labels_zh.size()) {
      const std::string& zh = p.scale_labels_zh[size_t(k - 1)];
      b.centred(x + 0.5f * bw, by + bh + 1.55f * b.small(), zh,
                b.fit(zh, b.small(), 0.0f, b.small(), 0.96f * bw));
    }
  }
  const float ry = by + bh + gap + words_h + gap;
  if (i > 0)
    b.target(l.margin, ry, l.margin + l.button_w, ry + row_h, StudyTargetAction::kBackItem,
             kBackText.twoLines(), 0, false, kQuietColour);
  b.target(b.w() - l.margin - l.button_w, ry, b.w() - l.margin, ry + row_h,
           StudyTargetAction::kSkipItem, kSkipText.twoLines(), 0, false, kQuietColour);
}

// The closing page: thanks, declined or stopped.
void donePage(PageBuilder& b, const StudyRunState& state, const FormLayout& l, float y) {
  const float bottom = b.foot() - 0.03f * b.h();
  if (state.declined()) {
    y = formHeading(b, l, y, kDeclinedTitle.en, kDeclinedTitle.zh);
    b.block(l.margin, y, std::string(kDeclinedBody.en) + "\n\n" + kDeclinedBody.zh, b.body(),
            l.wrap, bottom);
    return;
  }
  y = formHeading(b, l, y, (state.aborted() ? kStoppedTitle : kThanksTitle).twoLines());
  const Bilingual& body = state.aborted() ? kStoppedBody : kThanksBody;
  const std::string value = state.aborted() ? state.abortReason() : state.participantId();
  char en[512], zh[512];
  std::snprintf(en, sizeof en, body.en, value.c_str());
  std::snprintf(zh, sizeof zh, body.zh, value.c_str());
  b.block(l.margin, y, std::string(en) + "\n\n" + zh, b.body(), l.wrap, bottom);
}

// A protocol's text as a paragraph flows: the TOML's line breaks inside a paragraph are the
// file's, not the author's; blank lines part paragraphs.
std::string flowed(const std::string& text) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\n') {
      out += text[i];
    } else if (i + 1 < text.size() && text[i + 1] == '\n') {
      out += "\n\n";
      while (i + 1 < text.size() && text[i + 1] == '\n') ++i;
    } else if (i + 1 < text.size() && !out.empty()) {
      out += ' ';
    }
  }
  return out;
}

void formPage(PageBuilder& b, const StudyRunState& state, const StudyPageInput& input) {
  const StudyProtocol& p = state.protocol();
  const float margin = 0.06f * b.w();
  const float wrap = b.w() - 2 * margin;
  const float button_w = 0.22f * b.w(), button_h = std::min(0.1f * b.h(), 0.2f * b.foot());
  const float button_y = b.foot() - 0.03f * b.h() - button_h;
  const FormLayout l{margin, wrap, button_w, button_h, button_y};
  const float text_bottom = button_y - 0.03f * b.h();
  b.fill(kBackground);
  float y = b.top() + 0.05f * b.h();
  const auto continueButton = [&] {
    b.target(0.5f * b.w() - button_w * 0.5f, button_y, 0.5f * b.w() + button_w * 0.5f,
             button_y + button_h, StudyTargetAction::kContinue, kContinueText.twoLines());
  };
  switch (state.stage()) {
    case StudyStageKind::kConsent: {
      y = formHeading(b, l, y, kConsentTitle.en, kConsentTitle.zh);
      b.block(margin, y, flowed(p.consent), b.body(), wrap, text_bottom);
      // Agree and decline side by side, the same size: declining is as easy as agreeing.
      const float gap = 0.04f * b.w();
      b.target(0.5f * (b.w() - gap) - button_w, button_y, 0.5f * (b.w() - gap), button_y + button_h,
               StudyTargetAction::kAgree, kAgreeText.twoLines());
      b.target(0.5f * (b.w() + gap), button_y, 0.5f * (b.w() + gap) + button_w, button_y + button_h,
               StudyTargetAction::kDecline, kDeclineText.twoLines(), 0, false, kQuietColour);
      break;
    }
    case StudyStageKind::kParticipant: {
      y = formHeading(b, l, y, kParticipantTitle.en, kParticipantTitle.zh);
      const float code = std::min(2.4f * b.title(), 0.3f * (text_bottom - y));
      b.centred(0.5f * b.w(), y + 0.3f * code, state.participantId(), code, kStudyHintColour);
      b.block(margin, y + 1.8f * code, kParticipantBody.twoLines(), b.body(), wrap, text_bottom);
      continueButton();
      break;
    }
    case StudyStageKind::kIntroduction: {
      y = formHeading(b, l, y, kIntroductionTitle.en, kIntroductionTitle.zh);
      std::string text = flowed(p.introduction.text);
      if (!p.introduction.video.empty())
        text += "\n(The operator plays the video " + p.introduction.video + ".)";
      b.block(margin, y, text, b.body(), wrap, text_bottom);
      continueButton();
      break;
    }
    case StudyStageKind::kDemographics:
      demographicsForm(b, state, input, l, y);
      break;
    case StudyStageKind::kQuestionnaire:
      questionnaireForm(b, state, l, y);
      break;
    case StudyStageKind::kFreeText: {
      const FreeTextQuestion& q = p.free_text[size_t(state.freeTextIndex())];
      y = formHeading(b, l, y,
                      numbered(kCommentsTitle, state.freeTextIndex() + 1, int(p.free_text.size())));
      y = b.block(margin, y, q.prompt, b.body(), wrap, y + 3.2f * b.body());
      keyboard(b, input, p.keyboard, y + 0.6f * b.body(), false);
      break;
    }
    case StudyStageKind::kDone:
      donePage(b, state, l, y);
      break;
    default:
      break;
  }
}

// The panel's column: x0 and its text width; the countdown's place above the foot line (its
// English, then its Chinese under it at `countdown_zh_size`).
struct PanelLayout {
  float x0, pad, wrap;
  float countdown_size, countdown_top, countdown_zh_size;
};

PanelLayout panelLayout(const PageBuilder& b) {
  PanelLayout l;
  l.x0 = kStudyPanelLeft * b.w(), l.pad = 0.012f * b.w();
  l.wrap = b.w() - l.x0 - 2 * l.pad;
  // Big, but within the column at any width ("0:00" digits are as wide as any).
  l.countdown_size = b.fit("Time left 00:00", 1.5f * b.title(), 0.0f, 1.5f * b.title(), l.wrap);
  l.countdown_zh_size = b.small();
  const float zh_h = b.size("剩余时间 00:00", l.countdown_zh_size, 0.0f)[1];
  l.countdown_top = b.foot() - 0.012f * b.h() - zh_h - l.countdown_size;
  return l;
}

// The task's "I'm done": one target; tapped, a question with "Yes, I'm done" and "Keep
// painting" in its place (a stray tap near the canvas's edge does not end a task). Returns the
// top of what it placed.
float doneTargets(PageBuilder& b, const PanelLayout& l, bool asked) {
  const float x0 = l.x0 + l.pad, x1 = b.w() - l.pad;
  const float h = 0.085f * b.h(), gap = 0.01f * b.w();
  // Just above the countdown, where the task's time is read.
  const float ask_h = 2.7f * b.small();
  float y = l.countdown_top - 0.02f * b.h() - h - (asked ? ask_h : 0.0f);
  const float top = y;
  if (!asked) {
    b.target(x0, y, x1, y + h, StudyTargetAction::kDone, kDoneText.twoLines(), 0, false,
             kDoneColour);
    return top;
  }
  b.block(x0, y, kDoneAskText.twoLines(), b.small(), l.wrap, y + ask_h - 0.2f * b.small(),
          kStudyHintColour);
  y += ask_h;
  const float mid = 0.5f * (x0 + x1);
  b.target(x0, y, mid - 0.5f * gap, y + h, StudyTargetAction::kDoneConfirm, kDoneYesText.twoLines(),
           0, false, kDoneColour);
  b.target(mid + 0.5f * gap, y, x1, y + h, StudyTargetAction::kDoneCancel,
           kKeepPaintingText.twoLines(), 0, false, kQuietColour);
  return top;
}

// The task's words, picture and "I'm done", from y down.
void taskPanel(PageBuilder& b, const StudyRunState& state, const StudyPageInput& input,
               const PanelLayout& l, float y) {
  const StudyTask* task = state.task();
  const float x = l.x0 + l.pad;
  float bottom;
  if (state.closing()) {
    // No "I'm done" once the task has ended: what happens now, where it stood.
    const std::string ended =
        (state.closingWhy() == "time up" ? kTimeUpText : kFinishingText).twoLines();
    const float top = l.countdown_top - 0.02f * b.h() - 0.085f * b.h() - 2.7f * b.small();
    b.block(x, top, ended, b.body(), l.wrap, l.countdown_top - 0.02f * b.h(), kStudyHintColour);
    bottom = top - l.pad;
  } else {
    bottom = doneTargets(b, l, input.done_asked) - l.pad;
  }
  // "Task 2 of 4" over the task's own title, which keeps to one line when it can (a title
  // such as "Cloud 2: cloud photograph 1" wrapped after "Task 2 of 4: " left its number alone
  // on the second line).
  const std::string order = numbered(kTaskOrderText, state.position().order + 1, state.taskCount());
  b.text(x, y, order, b.small(), kStudyHintColour);
  y += b.size(order, b.small(), 0.0f)[1] + 0.25f * b.small();
  const float title_size = b.fit(task->title, b.body(), 0.0f, 1.5f * b.body(), l.wrap);
  if (b.size(task->title, title_size, 0.0f)[0] <= l.wrap) {
    b.text(x, y, task->title, title_size);
    y += b.size(task->title, title_size, 0.0f)[1];
  } else {
    y = b.block(x, y, task->title, title_size, l.wrap, y + 2.6f * b.body());
  }
  y += 0.5f * b.body();
  if (input.saved_task > 0) {
    // The task before this one, saved: said here for a few seconds.
    const StudyWords saved = studyTaskSavedText(input.saved_task, input.saved_pending);
    y = b.block(x, y, saved.en + " " + saved.zh, b.small(), l.wrap, y + 2.4f * b.small(),
                kSavedColour) +
        0.5f * b.small();
  }
  // What to do and how it ends, under the picture; the picture takes the room left.
  const std::string how = std::string(kTaskHowText.en) + " " + kTaskHowText.zh;
  const float how_size = b.fit(how, b.small(), l.wrap, 4.0f * b.small());
  const float how_h = b.size(how, how_size, l.wrap)[1];
  if (input.image_aspect > 0.0f) {
    const float room = bottom - y - how_h - l.pad;
    const float ih = std::max(0.0f, std::min({l.wrap / input.image_aspect, 0.4f * b.h(), room}));
    const float w = ih * input.image_aspect;
    b.setImage(x, y, x + w, y + ih);
    y += ih + l.pad;
  }
  b.text(x, y, how, how_size, kStudyTextColour, l.wrap);
}

void paintingPanel(PageBuilder& b, const StudyRunState& state, const StudyPageInput& input) {
  // A column at the right: what this stage is, the reference image, the instruction and its
  // live check, the countdown. The painter's status line stays visible along the top (under
  // the operator's band when that is shown).
  const StudyProtocol& p = state.protocol();
  const PanelLayout l = panelLayout(b);
  const float top = std::max(0.075f * b.h(), b.top());
  b.box(l.x0, top, b.w(), b.foot(), kPanel);
  float y = top + l.pad;
  const float x = l.x0 + l.pad;
  const double left = state.secondsLeft(input.now_ns);
  const float bottom = left >= 0 ? l.countdown_top - l.pad : b.foot() - l.pad;
  switch (state.stage()) {
    case StudyStageKind::kTutorial: {
      const TutorialStep& step = p.tutorial[size_t(state.tutorialStep())];
      y = b.block(x, y,
                  numbered(kTutorialStepText, state.tutorialStep() + 1, int(p.tutorial.size())),
                  b.body(), l.wrap, y + 2.5f * b.body()) +
          0.6f * b.body();
      // The step's words take the room the check and the clock leave.
      const float rest = 4.4f * b.small() + 2.8f * b.small();
      y = b.block(x, y, step.instruction, 1.1f * b.body(), l.wrap, bottom - rest) +
          0.8f * b.small();
      const std::string check = std::string(kToFinishText.en) + ": " + input.check.en + "\n" +
                                kToFinishText.zh + "：" + input.check.zh;
      y = b.block(x, y, check, b.small(), l.wrap, bottom - 2.8f * b.small()) + 0.6f * b.small();
      // The tutorial has a planned length (§7.5: ten minutes), not a limit: it ends when its
      // steps are done (or skipped by the operator).
      const int elapsed = int(state.stageSeconds(input.now_ns));
      char en[96], zh[96];
      std::snprintf(en, sizeof en, kTutorialTimeText.en, elapsed / 60, elapsed % 60,
                    p.tutorial_minutes);
      std::snprintf(zh, sizeof zh, kTutorialTimeText.zh, elapsed / 60, elapsed % 60,
                    p.tutorial_minutes);
      b.block(x, y, std::string(en) + "\n" + zh, b.small(), l.wrap, bottom);
      break;
    }
    case StudyStageKind::kFreeDrawing:
      y = b.block(x, y, kFreeDrawingTitle.twoLines(), b.body(), l.wrap, y + 2.5f * b.body()) +
          0.6f * b.body();
      b.block(x, y, flowed(p.free_drawing.text), b.small(), l.wrap, bottom);
      break;
    case StudyStageKind::kTask:
      taskPanel(b, state, input, l, y);
      break;
    default:
      break;
  }
  if (left >= 0) {
    const std::string clock = countdownText(left);
    char en[64], zh[64];
    std::snprintf(en, sizeof en, kTimeLeftText.en, clock.c_str());
    std::snprintf(zh, sizeof zh, kTimeLeftText.zh, clock.c_str());
    const uint32_t colour = left <= 59.0 ? 0xff8060ffu : kStudyTextColour;  // red from 0:59
    b.text(x, l.countdown_top, en, l.countdown_size, colour);
    b.text(x, l.countdown_top + b.size(en, l.countdown_size, 0.0f)[1], zh, l.countdown_zh_size,
           colour);
  }
}

void operatorChooser(PageBuilder& b, const StudyRunState& state) {
  b.box(0, 0, b.w(), b.h(), kVeil);
  const OperatorAction action = state.choosingFor();
  const std::vector<std::string>& reasons = operatorReasons(action);
  const float x0 = 0.25f * b.w(), x1 = 0.75f * b.w();
  float y = b.top() + 0.06f * b.h();
  b.centred(0.5f * b.w(), y,
            std::string("Operator: why ") +
                (action == OperatorAction::kPause ? "pause?"
                 : action == OperatorAction::kSkip
                     ? (state.stage() == StudyStageKind::kTutorial ? "skip this step?"
                                                                   : "skip this stage?")
                     : "abort the session?"),
            b.title());
  y += 1.8f * b.title();
  // Each reason a row, Cancel under them: rows shrink when the room above the foot is short.
  const float gap = 0.012f * b.h();
  const float rows = float(reasons.size()) + 1.0f;
  const float bh = std::min(0.085f * b.h(), (b.foot() - y - 2 * gap) / rows - gap);
  for (size_t i = 0; i < reasons.size(); ++i) {
    b.target(x0, y, x1, y + bh, StudyTargetAction::kReason,
             std::to_string(i + 1) + "  " + reasons[i], int(i));
    y += bh + gap;
  }
  b.target(x0, y + gap, x0 + 0.4f * (x1 - x0), y + gap + bh, StudyTargetAction::kCancel,
           "Cancel (Esc)", 0, false, kQuietColour);
}

void pausedVeil(PageBuilder& b, const StudyRunState& state) {
  b.box(0, 0, b.w(), b.h(), kVeil);
  const float y = b.top() + 0.3f * (b.foot() - b.top());
  // "Paused" big over its Chinese, then who paused and how it goes on, each English over Chinese.
  b.centred(0.5f * b.w(), y, kPausedTitle.en, 2.0f * b.title());
  b.centred(0.5f * b.w(), y + 2.3f * b.title(), kPausedTitle.zh, 1.2f * b.title());
  const std::string by = kPausedBy.en + state.pauseReason();
  float line = y + 4.0f * b.title();
  for (const std::string& words :
       {by, std::string(kPausedBy.zh), std::string(kPausedHow.en), std::string(kPausedHow.zh)}) {
    b.centred(0.5f * b.w(), line, words, b.fit(words, b.body(), 0, b.body(), 0.94f * b.w()));
    line += 1.5f * b.body();
  }
}

}  // namespace

StudyTextMeasure studyPageFont(const StudyProtocol& protocol, std::string* error) {
  auto font = std::make_shared<UiOverlay>();
  font->addGlyphs(studyPageText(protocol));
  if (!font->initFont(error)) return nullptr;
  return [font](const UiLabel& label, float rect[4]) { font->labelRect(label, rect); };
}

void studyTextEstimate(const UiLabel& label, float rect[4]) {
  // Greedy word wrap over code points: Latin ~0.56 em, CJK 1 em (a line breaks after any CJK
  // character), one em per line, as ImGui sets Noto Sans CJK.
  const float em = label.size_px, wrap = label.centred ? 0.0f : label.wrap_width;
  float widest = 0.0f, line = 0.0f, word = 0.0f;
  int lines = 1;
  const auto flush_word = [&] {
    if (wrap > 0.0f && line > 0.0f && line + word > wrap) {
      widest = std::max(widest, line);
      line = 0.0f;
      ++lines;
    }
    line += word;
    word = 0.0f;
  };
  for (size_t i = 0; i < label.text.size();) {
    const unsigned char c = static_cast<unsigned char>(label.text[i]);
    const size_t n = c < 0x80 ? 1 : c < 0xe0 ? 2 : c < 0xf0 ? 3 : 4;
    i += n;
    if (c == '\n') {
      flush_word();
      widest = std::max(widest, line);
      line = 0.0f;
      ++lines;
    } else if (c == ' ') {
      flush_word();
      line += 0.3f * em;
    } else {
      word += n >= 3 ? em : 0.56f * em;
      if (n >= 3) flush_word();
    }
  }
  flush_word();
  widest = std::max(widest, line);
  rect[0] = label.centred ? label.x - 0.5f * widest : label.x;
  rect[1] = label.y;
  rect[2] = rect[0] + widest;
  rect[3] = label.y + em * float(lines);
}

StudyWords studyTaskSavedText(int task, bool pending) {
  const Bilingual& words = pending ? kTaskKeptText : kTaskSavedText;
  char en[96], zh[96];
  std::snprintf(en, sizeof en, words.en, task);
  std::snprintf(zh, sizeof zh, words.zh, task);
  return {en, zh};
}

std::string studyPageText(const StudyProtocol& p) {
  std::string text;
  for (const Bilingual& b :
       {kAgreeText,     kDeclineText,        kDeclinedTitle,   kDeclinedBody,
        kDoneText,      kDoneAskText,        kDoneYesText,     kKeepPaintingText,
        kTimeUpText,    kFinishingText,      kTaskSavedText,   kTaskKeptText,
        kTaskHowText,   kTimeLeftText,       kContinueText,    kOkText,
        kSkipText,      kBackText,           kDeleteText,      kSpaceText,
        kConsentTitle,  kParticipantTitle,   kParticipantBody, kIntroductionTitle,
        kAboutYouTitle, kQuestionnaireTitle, kCommentsTitle,   kThanksTitle,
        kStoppedTitle,  kTutorialStepText,   kToFinishText,    kTutorialTimeText,
        kTaskOrderText, kPausedTitle,        kPausedBy,        kPausedHow,
        kThanksBody,    kStoppedBody,        kFreeDrawingTitle})
    text += b.zh;
  text += studyWaitingZhText() + tutorialWordsZhText();
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

namespace {

// The foot line's words: what the page waits for, its English over its Chinese. A task that
// just ended is said on the page after it: in the task panel when a task follows, else at the
// head of the foot line.
std::string footText(const StudyRunState& state, const StudyPageInput& input) {
  StudyWords foot = state.waitingWords(input.now_ns);
  if (input.saved_task > 0 && state.stage() != StudyStageKind::kTask) {
    const StudyWords saved = studyTaskSavedText(input.saved_task, input.saved_pending);
    foot = {saved.en + "  " + foot.en, saved.zh + "  " + foot.zh};
  }
  return foot.en + "\n" + foot.zh;
}

}  // namespace

float studyFootHeight(const StudyRunState& state, const StudyPageInput& input, int width,
                      int height) {
  StudyPage page;
  PageBuilder b(&page, input, width, height);
  b.frame(input.storage_warning, footText(state, input));
  return b.h() - b.foot();
}

StudyPage buildStudyPage(const StudyRunState& state, const StudyPageInput& input, int width,
                         int height) {
  StudyPage page;
  PageBuilder b(&page, input, width, height);
  b.frame(input.storage_warning, footText(state, input));
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
  if (state.choosing())
    operatorChooser(b, state);
  else if (state.paused())
    pausedVeil(b, state);
  b.drawFrame();
  return page;
}

}  // namespace cb
