// Every page of the bundled study protocol laid out at 1920x1080, 1280x720, 1366x768 and
// 1024x768, with and without the operator's red band, measured with the real font (Noto Sans CJK
// through the runner's own UiOverlay): consent, participant code, introduction, each tutorial
// step, free drawing, a task (with a wide and a tall picture, "I'm done" and its question, the
// last minute, time up), each demographic field (a refused answer shown), each questionnaire item,
// each free-text question, the end (thanks, declined, stopped), the operator's chooser and the
// pause veil; the task that ended before, said saved (or kept) on the next task's panel and on
// the first demographics page's foot line. On each page:
// - every word and target lies on the screen;
// - no two words overlap, no two targets overlap, a target's words lie inside it and no other
//   words touch a target;
// - the operator's band and the foot line overlap nothing but their own words;
// - the task's picture overlaps no words or targets;
// - on the painting pages, the painter's first-screen hint (drawn over the painter's canvas,
//   above the foot line's height the runner passes it) overlaps neither the foot line nor the
//   band and lies on the screen;
// - the foot line says what the page waits for in English, then in Chinese (the state's
//   waitingWords; English first, its Chinese after), and every character of every word on the
//   page is in the font atlas studyPageText fills (none would be drawn as a box);
// - every button the participant taps (Continue, OK, Skip, Back, delete, space, "I agree", "I'm
//   done" and its question's answers) carries Chinese under its English, and each of the panel's
//   and the pause veil's own words ("Tutorial: step", "To finish this step", "Tutorial time", "Task
//   N of M", "Paused", ...) carries its Chinese in the same label or the one right after it; each
//   of those words is seen on some page (the check is not vacuous).
//
// CB_KEEP_FRAMES=DIR writes each 1920x1080 page as layout_<page>[_band].png (and each 1024x768
// page as layout_<page>[_band]_1024x768.png) (the page's boxes
// and words over black; the picture's place as a grey box; the painter's canvas is not drawn).
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <map>
#include <sstream>

#include "app/core/config_paths.h"
#include "app/render/hud_overlay.h"
#include "app/render/image_io.h"
#include "app/shell/painter/painter_messages.h"
#include "app/shell/study/study_page.h"
#include "app/study/protocol.h"

#include "tests/support/test_display.h"

namespace cb {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

// Float positions are rounded to pixels when drawn: half a pixel of overlap is not an overlap.
constexpr float kPixelSlack = 0.5f;

struct Rect {
  float x0, y0, x1, y1;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
};

bool overlaps(const Rect& a, const Rect& b) {
  return !a.empty() && !b.empty() && a.x0 + kPixelSlack < b.x1 && b.x0 + kPixelSlack < a.x1 &&
         a.y0 + kPixelSlack < b.y1 && b.y0 + kPixelSlack < a.y1;
}
bool inside(const Rect& a, const Rect& outer) {
  return a.x0 + kPixelSlack >= outer.x0 && a.y0 + kPixelSlack >= outer.y0 &&
         a.x1 - kPixelSlack <= outer.x1 && a.y1 - kPixelSlack <= outer.y1;
}
bool holdsCentre(const Rect& outer, const Rect& a) {
  const float x = 0.5f * (a.x0 + a.x1), y = 0.5f * (a.y0 + a.y1);
  return !outer.empty() && x >= outer.x0 && x < outer.x1 && y >= outer.y0 && y < outer.y1;
}
std::string str(const Rect& r) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.0f,%.0f)-(%.0f,%.0f)", r.x0, r.y0, r.x1, r.y1);
  return text;
}
std::string shortText(const std::string& text) {
  std::string s = text.substr(0, 40);
  for (char& c : s)
    if (c == '\n') c = ' ';
  return "\"" + s + (text.size() > 40 ? "...\"" : "\"");
}

// Every overlap and every piece off the screen on `page`, one line each ("" when none).
std::string layoutFaults(const StudyPage& page, const UiOverlay& font, int w, int h) {
  std::ostringstream out;
  const Rect screen{0, 0, float(w), float(h)};
  const Rect band{page.band[0], page.band[1], page.band[2], page.band[3]};
  const Rect foot{page.foot[0], page.foot[1], page.foot[2], page.foot[3]};
  const Rect image{page.image[0], page.image[1], page.image[2], page.image[3]};
  std::vector<Rect> words;
  for (const UiLabel& l : page.labels) {
    float r[4];
    font.labelRect(l, r);
    words.push_back({r[0], r[1], r[2], r[3]});
  }
  std::vector<Rect> targets;
  for (const StudyTarget& t : page.targets) targets.push_back({t.x0, t.y0, t.x1, t.y1});
  const auto word = [&](size_t i) { return shortText(page.labels[i].text) + " " + str(words[i]); };
  const auto target = [&](size_t i) {
    return "target " + shortText(page.targets[i].label) + " " + str(targets[i]);
  };
  for (size_t i = 0; i < words.size(); ++i) {
    if (!inside(words[i], screen)) out << "off the screen: " << word(i) << "\n";
    for (size_t j = i + 1; j < words.size(); ++j)
      if (overlaps(words[i], words[j]))
        out << "words overlap: " << word(i) << " / " << word(j) << "\n";
    for (size_t t = 0; t < targets.size(); ++t) {
      if (holdsCentre(targets[t], words[i]) ? !inside(words[i], targets[t])
                                            : overlaps(words[i], targets[t]))
        out << "words and target: " << word(i) << " / " << target(t) << "\n";
    }
    for (const auto& [name, block] : {std::pair{"operator band", band}, {"foot line", foot}})
      if (holdsCentre(block, words[i]) ? !inside(words[i], block) : overlaps(words[i], block))
        out << "words and " << name << " " << str(block) << ": " << word(i) << "\n";
    if (overlaps(words[i], image)) out << "words on the picture: " << word(i) << "\n";
  }
  for (size_t t = 0; t < targets.size(); ++t) {
    if (!inside(targets[t], screen)) out << "off the screen: " << target(t) << "\n";
    for (size_t u = t + 1; u < targets.size(); ++u)
      if (overlaps(targets[t], targets[u]))
        out << "targets overlap: " << target(t) << " / " << target(u) << "\n";
    for (const auto& [name, block] :
         {std::pair{"operator band", band}, {"foot line", foot}, {"picture", image}})
      if (overlaps(targets[t], block)) out << name << " on " << target(t) << "\n";
  }
  if (!image.empty() && (overlaps(image, band) || overlaps(image, foot) || !inside(image, screen)))
    out << "the picture " << str(image) << " under the band or foot line or off the screen\n";
  if (!band.empty() && overlaps(band, foot)) out << "the band and the foot line overlap\n";
  return out.str();
}

// Whether `text` holds a CJK ideograph (U+4E00..U+9FFF: three UTF-8 bytes from E4 to E9).
bool hasCjk(const std::string& text) {
  for (size_t i = 0; i + 2 < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0xe4 && c <= 0xe9) return true;
  }
  return false;
}

// What is wrong with the foot line of `page` and the glyphs of its words ("" when nothing).
std::string wordsFaults(const StudyPage& page, const StudyWords& waiting, const UiOverlay& font) {
  std::ostringstream out;
  if (waiting.en.empty() || !hasCjk(waiting.zh))
    out << "waitingWords lacks a language: \"" << waiting.en << "\" / \"" << waiting.zh << "\"\n";
  const UiLabel* foot = nullptr;
  for (const UiLabel& l : page.labels)
    if (l.y >= page.foot[1] && l.text.find(waiting.en) != std::string::npos) foot = &l;
  if (!foot) {
    out << "no foot line says \"" << waiting.en << "\"\n";
  } else {
    const size_t en = foot->text.find(waiting.en), zh = foot->text.find(waiting.zh);
    if (zh == std::string::npos || zh < en + waiting.en.size())
      out << "the foot line lacks the Chinese after the English: \"" << foot->text << "\"\n";
  }
  for (const UiLabel& l : page.labels)
    if (const int missing = font.missingGlyphs(l.text); missing != 0)
      out << missing << " characters not in the font atlas: " << shortText(l.text) << "\n";
  return out.str();
}

// The participant's buttons: their label must hold Chinese (the keyboard's letter keys, the
// demographic choices, the scale's numbers and the operator's chooser are not among them).
bool participantButton(const StudyTarget& t) {
  switch (t.action) {
    case StudyTargetAction::kAgree:
    case StudyTargetAction::kDecline:
    case StudyTargetAction::kContinue:
    case StudyTargetAction::kSkipItem:
    case StudyTargetAction::kBackItem:
    case StudyTargetAction::kBackspace:
    case StudyTargetAction::kOk:
    case StudyTargetAction::kSkipField:
    case StudyTargetAction::kDone:
    case StudyTargetAction::kDoneConfirm:
    case StudyTargetAction::kDoneCancel:
      return true;
    case StudyTargetAction::kKey:
      return t.text == " ";  // the space bar
    default:
      return false;
  }
}

// The English words the pages draw themselves (beside the protocol's texts), each of which must
// carry its Chinese.
const char* const kOwnWords[] = {"Tutorial: step",
                                 "To finish this step",
                                 "Tutorial time",
                                 "Task ",
                                 "Paused",
                                 "by the operator",
                                 "The session goes on",
                                 "Your participant code",
                                 "Everything recorded today",
                                 "Questionnaire: item",
                                 "Free drawing",
                                 "Thank you",
                                 "Session stopped",
                                 "Your answers and clouds",
                                 "The operator stopped"};

// Every participant button and page word on `page` without Chinese ("" when none); counts
// the page words seen in `seen`.
std::string untranslated(const StudyPage& page, std::map<std::string, int>* seen) {
  std::ostringstream out;
  for (const StudyTarget& t : page.targets)
    if (participantButton(t) && !hasCjk(t.label))
      out << "a button without Chinese: " << shortText(t.label) << "\n";
  for (size_t i = 0; i < page.labels.size(); ++i)
    for (const char* words : kOwnWords) {
      if (page.labels[i].text.rfind(words, 0) != 0) continue;
      ++(*seen)[words];
      const bool next = i + 1 < page.labels.size() && hasCjk(page.labels[i + 1].text);
      if (!hasCjk(page.labels[i].text) && !next)
        out << "words without their Chinese: " << shortText(page.labels[i].text) << "\n";
    }
  return out.str();
}

// A realistic operator band: the disk-full text with two tasks' files waiting.
const char* const kBandText =
    "OPERATOR: the session folder cannot be written for 12 s: No space left on device. Nothing "
    "recorded is lost yet (33073 KiB held in memory; waiting to be written: "
    "tasks/cloud1.{vdb,cbvol,exr,png}, tasks/cloud2.{vdb,cbvol,exr,png}); free space on the "
    "disk and the session carries on writing.";

// A session at the start of a step: in Camera mode from a view of its own, nothing counted.
TutorialState freshSession() {
  TutorialState s;
  s.words = {
      {"mode", "camera"}, {"camera_view", "free"}, {"brush", "2d"}, {"erase_tool", "rub-out"}};
  for (const TutorialVariable& v : tutorialVariables())
    if (v.kind != ConditionKind::kWord) s.numbers[std::string(v.name)] = 0;
  s.numbers["camera_elevation_deg"] = 30;
  s.numbers["canvas_altitude"] = 128;
  return s;
}

struct Size {
  int w, h;
};
const Size kSizes[] = {{1920, 1080}, {1280, 720}, {1366, 768}, {1024, 768}};

class StudyPageLayout : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string error;
    display_ = test::openTestDisplay(1920, 1080, &error);
    ASSERT_TRUE(display_) << error;
    protocol_ = loadStudyProtocol(defaultStudyProtocolPath());
    font_.addGlyphs(studyPageText(protocol_));
    ASSERT_TRUE(font_.init(&error)) << error;
    keep_ = std::getenv("CB_KEEP_FRAMES") ? std::getenv("CB_KEEP_FRAMES") : "";
    if (!keep_.empty()) {
      ASSERT_TRUE(hud_.init(&error)) << error;
    }
  }

  // Checks the page of `state` with `input` at every size, with and without the band; keeps
  // the 1920x1080 pages when asked.
  void check(const StudyRunState& state, StudyPageInput input, const std::string& name) {
    ++pages_;
    for (const bool with_band : {false, true}) {
      input.storage_warning = with_band ? kBandText : "";
      for (const Size& s : kSizes) {
        const StudyPage page = buildStudyPage(state, input, s.w, s.h);
        const std::string faults = layoutFaults(page, font_, s.w, s.h) +
                                   wordsFaults(page, state.waitingWords(input.now_ns), font_) +
                                   untranslated(page, &seen_) + hintFaults(state, input, s);
        EXPECT_EQ(faults, "") << name << (with_band ? " with the operator's band" : "") << " at "
                              << s.w << "x" << s.h;
        if ((s.w == 1920 || s.w == 1024) && !keep_.empty())
          keep(page, s, name + (with_band ? "_band" : "") + (s.w == 1920 ? "" : "_1024x768"));
      }
    }
  }

  // Painting stages: the painter's first-screen hint (mouse, no tablet: its widest lines) as
  // the runner has it drawn, in the canvas left of the panel and above the foot line's height
  // (studyFootHeight), against the page the runner lays out with its font: it must lie on the
  // screen, below the operator's band and clear of the foot line.
  std::string hintFaults(const StudyRunState& state, StudyPageInput input, Size s) {
    if (!isPaintingStage(state.stage()) || state.choosing() || state.paused()) return "";
    input.measure = [this](const UiLabel& l, float r[4]) { font_.labelRect(l, r); };
    const StudyPage page = buildStudyPage(state, input, s.w, s.h);
    UiOverlayState ui;
    ui.hint = firstScreenHint(true, false);
    ui.message_width = kStudyPanelLeft * float(s.w);
    ui.message_bottom = studyFootHeight(state, input, s.w, s.h);
    float r[4];
    font_.hintBox(s.w, s.h, ui, r);
    const Rect hint{r[0], r[1], r[2], r[3]};
    const Rect foot{page.foot[0], page.foot[1], page.foot[2], page.foot[3]};
    const Rect band{page.band[0], page.band[1], page.band[2], page.band[3]};
    ++hints_;
    std::ostringstream out;
    if (hint.empty()) out << "the painter's hint has no box\n";
    if (overlaps(hint, foot))
      out << "the painter's hint " << str(hint) << " overlaps the foot line " << str(foot) << "\n";
    if (overlaps(hint, band))
      out << "the painter's hint " << str(hint) << " overlaps the band " << str(band) << "\n";
    if (!inside(hint, Rect{0, 0, float(s.w), float(s.h)}))
      out << "the painter's hint " << str(hint) << " is off the screen\n";
    return out.str();
  }

  void keep(const StudyPage& page, Size s, const std::string& name) {
    const GLuint fb = display_->framebuffer();
    const float black[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    glClearNamedFramebufferfv(fb, GL_COLOR, 0, black);
    std::vector<HudItem> boxes = page.boxes;
    if (page.image[2] > page.image[0])
      boxes.push_back(makeHudRect(page.image[0], page.image[1], page.image[2], page.image[3],
                                  {0.5f, 0.5f, 0.5f, 1.0f}));
    hud_.draw(fb, s.w, s.h, boxes);
    glBindFramebuffer(GL_FRAMEBUFFER, fb);
    glViewport(0, 0, s.w, s.h);
    font_.drawLabels(s.w, s.h, page.labels);
    writePng(keep_ + "/layout_" + name + ".png", readFramebufferRgba8(fb, s.w, s.h));
  }

  std::unique_ptr<Display> display_;
  StudyProtocol protocol_;
  UiOverlay font_;
  HudOverlay hud_;
  std::string keep_;
  int pages_ = 0;
  int hints_ = 0;  // painting pages whose painter's hint was checked against the foot line
  std::map<std::string, int> seen_;  // kOwnWords: how often each was drawn
};

TEST_F(StudyPageLayout, NoPageOverlapsItselfTheBandOrTheFootAtAnySize) {
  int64_t t = 100 * kSecond;
  StudyRunState state(protocol_, 1, t);
  StudyPageInput input;
  input.now_ns = t;
  const auto at = [&](int64_t dt) { return input.now_ns = (t += dt); };

  ASSERT_EQ(state.stage(), StudyStageKind::kConsent);
  check(state, input, "consent");
  state.agree(at(kSecond));
  check(state, input, "participant");
  state.proceed(at(kSecond));
  check(state, input, "introduction");
  state.proceed(at(kSecond));

  ASSERT_EQ(state.stage(), StudyStageKind::kTutorial);
  for (size_t i = 0; i < protocol_.tutorial.size(); ++i) {
    // Each step's own checks in words, against a session that has done none of them yet.
    input.check = tutorialStepWords(protocol_.tutorial[i].expect, freshSession());
    check(state, input, "tutorial_" + std::to_string(i + 1));
    if (i == 0) {
      state.requestOperator(OperatorAction::kSkip, at(kSecond));
      check(state, input, "operator_skip");
      state.cancelChoice(at(kSecond));
      state.requestOperator(OperatorAction::kPause, at(kSecond));
      state.chooseReason(0, at(kSecond));
      check(state, input, "paused");
      state.requestOperator(OperatorAction::kPause, at(kSecond));  // resumes
      ASSERT_FALSE(state.paused());
    }
    state.completeTutorialStep(at(kSecond));
  }
  input.check = {};
  if (state.closing()) state.closeStage(at(kSecond));

  ASSERT_EQ(state.stage(), StudyStageKind::kFreeDrawing);
  check(state, input, "free_drawing");
  state.requestOperator(OperatorAction::kSkip, at(kSecond));
  state.chooseReason(0, at(kSecond));
  if (state.closing()) state.closeStage(at(kSecond));

  for (int task = 0; state.stage() == StudyStageKind::kTask; ++task) {
    const std::string n = std::to_string(task + 1);
    input.image_aspect = task % 2 ? 0.75f : 1.5f;  // a tall and a wide picture
    input.saved_task = task;  // the task before, said saved (none before the first)
    check(state, input, "task_" + n);
    input.saved_pending = true;  // its files wait for the disk
    check(state, input, "task_" + n + "_saved_pending");
    input.saved_task = 0, input.saved_pending = false;
    input.done_asked = true;
    check(state, input, "task_" + n + "_done_asked");
    input.done_asked = false;
    at(kSecond * int64_t(state.stageLimitSeconds() - 30));
    check(state, input, "task_" + n + "_last_minute");
    state.tick(at(31 * kSecond));  // time up: the page waits for the pen to lift
    EXPECT_TRUE(state.closing());
    check(state, input, "task_" + n + "_time_up");
    input.image_aspect = 0;
    if (state.closing()) state.closeStage(at(kSecond));
  }

  ASSERT_EQ(state.stage(), StudyStageKind::kDemographics);
  for (int f = 0; state.stage() == StudyStageKind::kDemographics; ++f) {
    input.saved_task = f == 0 ? int(protocol_.tasks.size()) : 0;  // the last task, saved
    check(state, input, "demographics_" + std::to_string(f + 1));
    input.saved_task = 0;
    input.typed = "12";
    input.message = "Please give a whole number from 16 to 99.";
    check(state, input, "demographics_" + std::to_string(f + 1) + "_refused");
    input.typed.clear(), input.message.clear();
    state.skipField(at(kSecond));
  }
  ASSERT_EQ(state.stage(), StudyStageKind::kQuestionnaire);
  for (int i = 0; state.stage() == StudyStageKind::kQuestionnaire; ++i) {
    check(state, input, "questionnaire_" + std::to_string(i + 1));
    state.answerItem(1 + i % 5, at(kSecond));
  }
  for (int i = 0; state.stage() == StudyStageKind::kFreeText; ++i) {
    input.typed = "The pen was easy to hold; the light was hard to place.";
    check(state, input, "free_text_" + std::to_string(i + 1));
    state.answerFreeText("", at(kSecond));
  }
  input.typed.clear();
  ASSERT_EQ(state.stage(), StudyStageKind::kDone);
  check(state, input, "end");

  StudyRunState declined(protocol_, 2, t);
  declined.decline(t);
  check(declined, input, "end_declined");
  StudyRunState stopped(protocol_, 3, t);
  stopped.agree(t);
  stopped.requestOperator(OperatorAction::kAbort, t);
  check(stopped, input, "operator_abort");
  stopped.chooseReason(0, t);
  check(stopped, input, "end_stopped");
  EXPECT_GT(hints_, 0) << "no painting page: the painter's hint went unchecked";
  for (const char* words : kOwnWords)
    EXPECT_GT(seen_[words], 0) << "no page drew \"" << words << "\": its Chinese went unchecked";
  std::printf("%d pages checked at %zu sizes, with and without the band\n", pages_,
              std::size(kSizes));
}

}  // namespace
}  // namespace cb
