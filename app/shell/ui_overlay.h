// The on-screen UI drawn with Dear ImGui inside the EGL frame ("Pen menu and on-screen
// UI"): a status line (mode, brush, mapping, canvas altitude, what the painter waits for) and
// the pen menu of big targets (thesis Fig. 3.7): the five modes, the current mode's commands,
// undo/redo, delete, open and save, each labelled with its key. The pen (or a mouse) drives it
// as ImGui's pointer; a tap on a target yields its Command. An always-visible menu button makes
// every command reachable for pens without side buttons.
//
// Text is set in Noto Sans CJK (fonts-noto-cjk), so labels may be Chinese; the atlas holds the
// Latin range plus exactly the CJK characters of the shipped labels.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "app/shell/command.h"
#include "app/shell/command_table.h"
#include "app/shell/kiosk/visitor_words.h"

struct ImGuiContext;

namespace cb {

// A line of text drawn by drawLabels (and by draw, over the painter: UiOverlayState::labels)
// (screens without the painter's status line and menu, such as calibration): at (x, y) in
// framebuffer pixels, y down; `centred` centres it on x.
struct UiLabel {
  float x = 0.0f, y = 0.0f;
  std::string text;
  float size_px = 28.0f;
  uint32_t rgba = 0xffffffffu;  // 0xRRGGBBAA
  bool centred = false;
  uint32_t background_rgba = 0;  // a box behind the text when its alpha is not 0
  float wrap_width = 0.0f;       // > 0: lines wrap at this width (pixels; not with `centred`)
};

struct UiOverlayState {
  std::string status;  // the status line
  std::string notice;  // a warning shown above it (edge-on view, errors), or empty
  bool menu_open = false;
  int mode = 2;  // Mode as an int (0 camera … 4 light), for the mode's commands
  bool can_undo = false, can_redo = false;
  bool visitor = false;    // kiosk visitor mode: operator targets are not shown
  bool animation = false;  // a morph or wind is shown (apply and leave are enabled)
  std::string toast;       // a transient answer under the status line (a save, a refused key)
  std::vector<std::string> hint;  // the first screen's lines, low in the middle, or none
  float message_width = 0.0f;     // toast and hint centred in [0, message_width] (0: the width)
  float message_bottom = 0.0f;    // pixels along the bottom the host covers: the hint is above
  std::vector<HelpSection> help;  // the help overlay (H or ?), or none
  std::vector<UiLabel> labels;    // words over the heads-up items (the statistics panel's)
  // A kiosk visitor's screen in the kiosk's words (visitor_words.h): the menu button's (closed,
  // open), the menu's rows (no key names) and, while the help is open, its lines; with them
  // the painter's own menu and help are not drawn.
  struct VisitorWords {
    std::string menu, close;
    std::vector<VisitorMenuRow> rows;
    std::vector<std::string> help;
  };
  std::optional<VisitorWords> visitor_words;
};

class UiOverlay {
 public:
  UiOverlay();
  ~UiOverlay();
  UiOverlay(const UiOverlay&) = delete;
  UiOverlay& operator=(const UiOverlay&) = delete;

  // Characters the font atlas must hold besides the shipped labels' (e.g. the kiosk's visitor
  // texts in Chinese); call before init().
  void addGlyphs(const std::string& utf8_text) { extra_glyphs_ += utf8_text; }
  // Creates the ImGui context, font atlas and GL objects (the GL context must be current).
  bool init(std::string* error);
  // Only the context and the font atlas (no GL): enough for labelRect, without a display.
  bool initFont(std::string* error);
  // The pointer (pen tip or mouse) in framebuffer pixels, y down.
  void pointer(float x, float y, bool down);
  // Draws the UI over the bound framebuffer of width × height and returns the commands of the
  // targets tapped since the last frame (a tap = press and release on the same target).
  std::vector<Command> draw(int width, int height, double dt_s, const UiOverlayState& state);
  // Draws the last draw()'s UI again over the bound framebuffer, only within `box` (x0, y0, x1,
  // y1; pixels, y down, half-open), each pixel as draw() drew it: the painter's late ink
  // re-blits the ink under the UI and draws the UI over it again. False when there is no such
  // draw to repeat (then nothing is drawn).
  bool redraw(const glm::ivec4& box);
  // Draws only `labels` over the bound framebuffer (the one font of every screen).
  void drawLabels(int width, int height, const std::vector<UiLabel>& labels);
  // The box drawLabels gives `label` (x0, y0, x1, y1 in framebuffer pixels: centred, wrapped,
  // one line height per line), after init() or initFont(); layouts measure their texts with it.
  void labelRect(const UiLabel& label, float rect[4]) const;
  // Whether the pointer is over a UI target (the painter then keeps the pen off the canvas).
  bool pointerOverUi() const { return over_ui_; }
  // Whether the last frame's status line fitted before the menu button (not clipped).
  bool statusFits() const { return status_fits_; }
  // Characters of `utf8_text` the font atlas lacks (0: every one is drawn); after init().
  int missingGlyphs(const std::string& utf8_text) const;
  // The screen rectangle of the menu button, for tests (x0, y0, x1, y1).
  const float* menuButtonRect() const { return menu_button_; }
  // The last frame's toast box (x0, y0, x1, y1; zero size: none), for tests.
  const float* toastRect() const { return toast_rect_; }
  // The last frame's first-screen hint box (x0, y0, x1, y1; zero size: none), for tests.
  const float* hintRect() const { return hint_rect_; }
  // The box the hint of `state` takes on a width x height screen (zero size: none), as draw()
  // places it, after init() or initFont(): layouts check it against what the host draws.
  void hintBox(int width, int height, const UiOverlayState& state, float rect[4]) const;
  // The rectangle of a command's target in the open menu, for tests; false when not shown.
  bool targetRect(Command command, float rect[4]) const;
  // Told every text any overlay draws (status, notice, answer, hint, targets, help, labels), as
  // drawn, for tests that check what a screen says; none by default. Not thread-safe: set it
  // while nothing draws.
  static void setTextObserver(std::function<void(const std::string&)> observer);

 private:
  void drawMessages(int width, int height, float bar_h, const UiOverlayState& state);
  void drawHelp(int width, int height, const std::vector<HelpSection>& help);
  // The open menu (a window of big targets); taps go to *tapped.
  void drawMenu(int width, int height, const UiOverlayState& state, int window_flags,
                std::vector<Command>* tapped);
  ImGuiContext* context_ = nullptr;
  bool ready_ = false;
  std::string extra_glyphs_;
  struct PointerState {
    float x, y;
    bool down;
  };
  // Pointer states since the last frame; a press and release between two frames are shown on
  // consecutive frames, so a quick tap is never lost.
  std::vector<PointerState> pointer_queue_;
  PointerState pointer_{-1.0f, -1.0f, false};
  bool over_ui_ = false;
  bool status_fits_ = true;
  bool last_draw_ = false;  // ImGui's draw data is draw()'s (redraw repeats it)
  float menu_button_[4] = {0, 0, 0, 0};
  float toast_rect_[4] = {0, 0, 0, 0};
  float hint_rect_[4] = {0, 0, 0, 0};
  struct Target {
    Command command;
    float rect[4];
  };
  std::vector<Target> targets_;
};

}  // namespace cb
