#include "app/shell/keymap.h"

#include <cctype>

#include <xkbcommon/xkbcommon-keysyms.h>

namespace cb {
namespace {

constexpr const char* kCommandNames[] = {"quit",
                                         "mode-camera",
                                         "mode-canvas",
                                         "mode-paint",
                                         "mode-erase",
                                         "mode-light",
                                         "menu",
                                         "next-brush",
                                         "next-mapping",
                                         "reset-camera",
                                         "view-top",
                                         "view-front",
                                         "view-left",
                                         "view-perspective",
                                         "space",
                                         "smaller",
                                         "larger",
                                         "brush-smaller",
                                         "brush-larger",
                                         "raise",
                                         "lower",
                                         "next-erase-tool",
                                         "toggle-circles",
                                         "toggle-stats",
                                         "delete-all",
                                         "undo",
                                         "redo",
                                         "save",
                                         "good-view",
                                         "open",
                                         "next-style",
                                         "operator-pause",
                                         "operator-skip",
                                         "operator-abort",
                                         "pan-drag",
                                         "pan-left",
                                         "pan-right",
                                         "pan-up",
                                         "pan-down",
                                         "morph",
                                         "wind",
                                         "wind-direction",
                                         "apply-animation",
                                         "leave-animation",
                                         "help"};
static_assert(sizeof(kCommandNames) / sizeof(kCommandNames[0]) == size_t(Command::kCount));

uint32_t lowerLetter(uint32_t keysym) {
  return keysym >= 'A' && keysym <= 'Z' ? keysym - 'A' + 'a' : keysym;
}

struct NamedKey {
  const char* name;
  uint32_t keysym;
};
constexpr NamedKey kNamedKeys[] = {
    {"space", XKB_KEY_space},
    {"esc", XKB_KEY_Escape},
    {"enter", XKB_KEY_Return},
    {"delete", XKB_KEY_Delete},
    {"up", XKB_KEY_Up},
    {"down", XKB_KEY_Down},
    {"left", XKB_KEY_Left},
    {"right", XKB_KEY_Right},
    {"minus", XKB_KEY_minus},
    {"plus", XKB_KEY_plus},
    {"bracketleft", XKB_KEY_bracketleft},
    {"bracketright", XKB_KEY_bracketright},
    {"pageup", XKB_KEY_Prior},
    {"pagedown", XKB_KEY_Next},
    {"f1", XKB_KEY_F1},
    {"f2", XKB_KEY_F2},
    {"f3", XKB_KEY_F3},
    {"f4", XKB_KEY_F4},
    {"f5", XKB_KEY_F5},
    {"f6", XKB_KEY_F6},
    {"f7", XKB_KEY_F7},
    {"f8", XKB_KEY_F8},
    {"f9", XKB_KEY_F9},
    {"f10", XKB_KEY_F10},
    {"f11", XKB_KEY_F11},
    {"f12", XKB_KEY_F12},
};

}  // namespace

const char* commandName(Command command) {
  return kCommandNames[int(command)];
}

std::optional<Command> parseCommandName(std::string_view name) {
  for (int i = 0; i < int(Command::kCount); ++i)
    if (name == kCommandNames[i]) return Command(i);
  return std::nullopt;
}

std::optional<Command> commandForKey(uint32_t keysym, uint32_t modifiers) {
  const uint32_t k = lowerLetter(keysym);
  const bool ctrl = modifiers & DisplayEvent::kCtrl;
  const bool shift = modifiers & DisplayEvent::kShift;
  if (ctrl && (modifiers & DisplayEvent::kAlt)) {
    if (k == 'p') return Command::kOperatorPause;
    if (k == 's') return Command::kOperatorSkip;
    if (k == 'a') return Command::kOperatorAbort;
    return std::nullopt;
  }
  if (ctrl) {
    if (k == 'z') return shift ? Command::kRedo : Command::kUndo;
    if (k == 'y') return Command::kRedo;
    if (k == 's') return Command::kSave;
    if (k == 'o') return Command::kOpen;
    return std::nullopt;  // Ctrl+anything else: nothing (no accidental commands)
  }
  if (shift) {
    // Shift+arrows pan the view; the plain arrows are the preset views.
    if (k == XKB_KEY_Left) return Command::kPanLeft;
    if (k == XKB_KEY_Right) return Command::kPanRight;
    if (k == XKB_KEY_Up) return Command::kPanUp;
    if (k == XKB_KEY_Down) return Command::kPanDown;
  }
  switch (k) {
    case XKB_KEY_Escape:
      return Command::kQuit;
    case 'q':
      return Command::kQuit;
    case '1':
      return Command::kModeCamera;
    case '2':
      return Command::kModeCanvas;
    case '3':
      return Command::kModePaint;
    case '4':
      return Command::kModeErase;
    case '5':
      return Command::kModeLight;
    case 'm':
      return Command::kMenu;
    case 'b':
      return Command::kNextBrush;
    case 'n':
      return Command::kNextMapping;
    case 'g':
      return Command::kGoodView;
    case 't':
      return Command::kNextStyle;
    case 'f':
      return Command::kMorph;
    case 'w':
      return Command::kWind;
    case 'd':
      return Command::kWindDirection;
    case 'a':
      return Command::kApplyAnimation;
    case 'x':
      return Command::kLeaveAnimation;
    case 'h':
    case XKB_KEY_question:
      return Command::kHelp;
    case 'r':
      return Command::kResetCamera;
    case 'v':
      return Command::kNextEraseTool;
    case 'p':
      return Command::kPanDrag;
    case 'c':
      return Command::kToggleCircles;
    case 's':
      return Command::kToggleStats;
    case XKB_KEY_Up:
      return Command::kViewTop;
    case XKB_KEY_Down:
      return Command::kViewFront;
    case XKB_KEY_Left:
      return Command::kViewLeft;
    case XKB_KEY_Right:
      return Command::kViewPerspective;
    case XKB_KEY_space:
      return Command::kSpace;
    case XKB_KEY_minus:
    case XKB_KEY_KP_Subtract:
    case XKB_KEY_underscore:
      return Command::kSmaller;
    case XKB_KEY_plus:
    case XKB_KEY_equal:
    case XKB_KEY_KP_Add:
      return Command::kLarger;
    case XKB_KEY_bracketleft:
    case XKB_KEY_braceleft:
      return Command::kBrushSmaller;
    case XKB_KEY_bracketright:
    case XKB_KEY_braceright:
      return Command::kBrushLarger;
    case XKB_KEY_Prior:
      return Command::kRaise;
    case XKB_KEY_Next:
      return Command::kLower;
    case XKB_KEY_Delete:
      return Command::kDeleteAll;
    default:
      return std::nullopt;
  }
}

std::optional<Command> commandFor(const DisplayEvent& event) {
  if (event.kind == DisplayEvent::Kind::Quit) return Command::kQuit;
  if (event.kind != DisplayEvent::Kind::KeyDown) return std::nullopt;
  return commandForKey(event.keysym, event.modifiers);
}

bool parseKeyList(std::string_view text, std::vector<DisplayEvent>* keys, std::string* error) {
  std::vector<std::string> tokens;
  bool compact = text.find(',') == std::string_view::npos;
  for (char c : text) compact = compact && std::isalnum(static_cast<unsigned char>(c));
  std::string lower(text);
  for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
  for (const NamedKey& named : kNamedKeys) compact = compact && lower != named.name;
  if (compact) {
    for (char c : text) tokens.emplace_back(1, c);
  } else {
    size_t start = 0;
    while (start <= text.size()) {
      const size_t comma = text.find(',', start);
      tokens.emplace_back(
          text.substr(start, comma == std::string_view::npos ? text.npos : comma - start));
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
  }
  for (std::string token : tokens) {
    for (char& c : token) c = char(std::tolower(static_cast<unsigned char>(c)));
    uint32_t modifiers = 0;
    const auto strip = [&](const char* prefix, uint32_t bit) {
      const std::string p(prefix);
      if (token.rfind(p, 0) == 0 && token.size() > p.size()) {
        token = token.substr(p.size());
        modifiers |= bit;
        return true;
      }
      return false;
    };
    while (strip("ctrl+", DisplayEvent::kCtrl) || strip("shift+", DisplayEvent::kShift) ||
           strip("alt+", DisplayEvent::kAlt)) {
    }
    uint32_t keysym = 0;
    if (token.size() == 1 && std::isalnum(static_cast<unsigned char>(token[0]))) {
      keysym = uint32_t(token[0]);
    } else {
      for (const NamedKey& named : kNamedKeys)
        if (token == named.name) keysym = named.keysym;
    }
    if (keysym == 0) {
      *error = "key '" + token +
               "' is not a letter, digit or one of space, esc, delete, up, down, left, right, "
               "minus, plus, bracketleft, bracketright, pageup, pagedown, f1-f12";
      return false;
    }
    keys->push_back(DisplayEvent::key(keysym, modifiers));
  }
  return true;
}

std::string keyLabel(Command command) {
  switch (command) {
    case Command::kQuit:
      return "Esc";
    case Command::kModeCamera:
      return "1";
    case Command::kModeCanvas:
      return "2";
    case Command::kModePaint:
      return "3";
    case Command::kModeErase:
      return "4";
    case Command::kModeLight:
      return "5";
    case Command::kMenu:
      return "M";
    case Command::kNextBrush:
      return "B";
    case Command::kNextMapping:
      return "N";
    case Command::kResetCamera:
      return "R";
    case Command::kViewTop:
      return "Up";
    case Command::kViewFront:
      return "Down";
    case Command::kViewLeft:
      return "Left";
    case Command::kViewPerspective:
      return "Right";
    case Command::kSpace:
      return "Space";
    case Command::kSmaller:
      return "-";
    case Command::kLarger:
      return "+";
    case Command::kRaise:
      return "PgUp";
    case Command::kLower:
      return "PgDn";
    case Command::kNextEraseTool:
      return "V";
    case Command::kToggleCircles:
      return "C";
    case Command::kToggleStats:
      return "S";
    case Command::kDeleteAll:
      return "Del";
    case Command::kUndo:
      return "Ctrl+Z";
    case Command::kRedo:
      return "Ctrl+Y";
    case Command::kSave:
      return "Ctrl+S";
    case Command::kGoodView:
      return "G";
    case Command::kOpen:
      return "Ctrl+O";
    case Command::kNextStyle:
      return "T";
    case Command::kOperatorPause:
      return "Ctrl+Alt+P";
    case Command::kOperatorSkip:
      return "Ctrl+Alt+S";
    case Command::kOperatorAbort:
      return "Ctrl+Alt+A";
    case Command::kPanDrag:
      return "P";
    case Command::kPanLeft:
      return "Shift+Left";
    case Command::kPanRight:
      return "Shift+Right";
    case Command::kPanUp:
      return "Shift+Up";
    case Command::kPanDown:
      return "Shift+Down";
    case Command::kMorph:
      return "F";
    case Command::kWind:
      return "W";
    case Command::kWindDirection:
      return "D";
    case Command::kApplyAnimation:
      return "A";
    case Command::kLeaveAnimation:
      return "X";
    case Command::kBrushSmaller:
      return "[";
    case Command::kBrushLarger:
      return "]";
    case Command::kHelp:
      return "H";
    default:
      return "";
  }
}

}  // namespace cb
