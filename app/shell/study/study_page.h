// What the study runner shows (app/shell/study/study_run_screen.h), laid out on the CPU from the
// runner's state (app/study/study_run_state.h) so tests know every target: the form pages
// (consent, participant code, introduction, demographics with the on-screen keyboard, the Likert
// questionnaire one item at a time, free text, the end), the panel beside the painter in the
// tutorial, free drawing and tasks (stage, instruction and its check, the countdown, the
// reference image's place), and the operator's reason chooser and pause veil over any stage.
// Every page says in words what it waits for at its foot, English over Chinese
// (StudyRunState::waitingWords). Pages are
// laid out from measured texts between the operator's band (when shown) and the foot line, so
// nothing overlaps at any screen size: long texts take a smaller size, boxes shrink to fit. The
// participant's buttons (consent, Continue, OK, Skip, Back, the keyboard's named keys, "I'm
// done") are labelled in English over Chinese, like the painter's menu, and so are the pages'
// own words (headings, the tutorial's step and clock, "Task N of M", the pause veil); the
// operator's chooser stays English.
//
// Drawn by the runner with the HUD overlay (boxes) and ui_overlay's labels (Noto Sans CJK).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "app/render/hud_overlay.h"
#include "app/shell/ui_overlay.h"
#include "app/study/study_run_state.h"
#include "app/study/tutorial_words.h"

namespace cb {

// What tapping a target does.
enum class StudyTargetAction {
  kAgree,         // consent
  kDecline,       // consent: "I do not agree" (the session ends)
  kContinue,      // participant code, introduction
  kAnswer,        // questionnaire: value 1..n
  kSkipItem,      // questionnaire: leave NA
  kBackItem,      // questionnaire: the previous item
  kKey,           // on-screen keyboard: `text` is typed
  kBackspace,     // on-screen keyboard
  kKeyboardPage,  // on-screen keyboard: value = the page (again: back to the letters)
  kChoice,        // demographics choice: `text` is the answer
  kOk,            // demographics / free text: take what was typed
  kSkipField,     // demographics / free text: NA
  kReason,        // operator chooser: value = reason index
  kCancel,        // operator chooser
  kDone,          // task panel: "I'm done" (asks to confirm)
  kDoneConfirm,   // task panel: "Yes, I'm done" (the task ends, end reason `done`)
  kDoneCancel,    // task panel: "Keep painting"
};

struct StudyTarget {
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  StudyTargetAction action = StudyTargetAction::kContinue;
  int value = 0;
  std::string text;  // kKey, kChoice
  std::string label;
  bool selected = false;  // shown highlighted (the answer given before)
  bool contains(float x, float y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
};

struct StudyPage {
  std::vector<HudItem> boxes;  // backgrounds and panels, under the targets
  std::vector<StudyTarget> targets;
  std::vector<UiLabel> labels;  // drawn last
  // Painting stages: where the reference image goes (x0, y0, x1, y1; zero size: none).
  float image[4] = {0, 0, 0, 0};
  // The operator's band along the top (zero size: none) and the line at the foot that says what
  // the page waits for: the page's words and targets keep clear of both.
  float band[4] = {0, 0, 0, 0};
  float foot[4] = {0, 0, 0, 0};
  // The first target with `action` (and `value` when >= 0), or null.
  const StudyTarget* find(StudyTargetAction action, int value = -1) const;
  const StudyTarget* hit(float x, float y) const;
};

// The box a label takes when drawn (x0, y0, x1, y1): the runner measures with its font
// (UiOverlay::labelRect); without one, studyTextEstimate.
using StudyTextMeasure = std::function<void(const UiLabel&, float rect[4])>;
// The runner's own measure (its font and glyphs for `protocol`) without a display, for laying
// out pages as the runner shows them (a recorded pen's taps); null with *error when the font is
// missing.
StudyTextMeasure studyPageFont(const StudyProtocol& protocol, std::string* error);
// A generous estimate of a label's box without a font (Latin ~0.56 em, CJK 1 em, lines of 1 em).
void studyTextEstimate(const UiLabel& label, float rect[4]);

// What the screen knows besides the state: the text typed so far, a message (a refused answer),
// the tutorial step's checks in words with their live status (tutorial_words.h), and the reference
// image's aspect (width / height; 0: none).
struct StudyPageInput {
  std::string typed;
  std::string message;
  StudyWords check;
  float image_aspect = 0.0f;
  int64_t now_ns = 0;
  bool painter_menu_open = false;  // the painter's pen menu is open: the panel steps aside
  bool done_asked = false;         // "I'm done" was tapped: the panel asks to confirm
  // The task that just ended (its number in the participant's order, from 1; 0: none), said
  // on the next page for a few seconds: saved, or kept and still being written (`pending`).
  int saved_task = 0;
  bool saved_pending = false;
  int keyboard_page = 0;  // the on-screen keyboard's page (kKeyboard*)
  // The operator's warning that the session folder cannot be written (study_storage_watch.h),
  // shown over every page; "" when writing works.
  std::string storage_warning;
  // How texts are measured, so the page fits its words between the band and the foot line;
  // null: studyTextEstimate.
  StudyTextMeasure measure;
};

// The on-screen keyboard's pages: letters, capitals (Shift), symbols and accented letters, and
// the protocol's own characters ([keyboard] in the protocol).
inline constexpr int kKeyboardLower = 0, kKeyboardUpper = 1, kKeyboardSymbols = 2,
                     kKeyboardProtocol = 3;

// The page of the current stage (a form, or the panel beside the painter), with the operator's
// chooser or pause veil over it when one is open.
StudyPage buildStudyPage(const StudyRunState& state, const StudyPageInput& input, int width,
                         int height);

// The height of the foot line along the bottom of `state`'s page (pixels; as buildStudyPage
// lays it out): the painter's first-screen hint keeps above it.
float studyFootHeight(const StudyRunState& state, const StudyPageInput& input, int width,
                      int height);

// What the next page says of the task that ended: "Task N saved." (or kept and being saved
// when its files wait for the disk), English and Chinese (StudyWords: study_waiting_words.h).
StudyWords studyTaskSavedText(int task, bool pending);

// Every text the pages may show beyond Latin: their own Chinese and the protocol's texts (the
// font atlas holds their characters).
std::string studyPageText(const StudyProtocol& protocol);

// Where the panel beside the painter begins (a fraction of the width; the canvas is left of it).
inline constexpr float kStudyPanelLeft = 0.72f;

// The colours of the page's boxes and targets (RGBA, straight alpha).
inline constexpr uint32_t kStudyTextColour = 0xf2f2f2ffu;
inline constexpr uint32_t kStudyHintColour = 0xffd970ffu;

}  // namespace cb
