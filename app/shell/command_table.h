// One table of the painter's commands as a person meets them: where each acts (every mode, or
// only some: thesis Appendix A's keys are mode keys — R and the arrows in Camera mode, PgUp/PgDn
// in Canvas mode, V in Erase mode), and its label in English and Chinese (the menu, the help
// overlay, a refused key's reason). keymap.h says which key gives a command; this says where
// it acts and what it is called.
#pragma once

#include <string>
#include <vector>

#include "app/session/ui_change.h"
#include "app/shell/command.h"

namespace cb {

// A text in the two languages of the menu (English first, Chinese second).
struct Bilingual {
  const char* en = "";
  const char* zh = "";
  // "English\n中文": the menu's two-line targets.
  std::string twoLines() const { return std::string(en) + "\n" + zh; }
  // "English / 中文": one line (status, messages).
  std::string oneLine() const { return std::string(en) + " / " + zh; }
};

// Modes as bits (1 << int(Mode)).
constexpr unsigned kEveryMode = 0x1f;
constexpr unsigned modeBit(Mode mode) {
  return 1u << unsigned(mode);
}

// The modes in which `command` acts (kEveryMode for a global command).
unsigned commandModes(Command command);
inline bool commandActsIn(Command command, Mode mode) {
  return (commandModes(command) & modeBit(mode)) != 0;
}
// The command's label; empty texts for a command without one (kCount).
Bilingual commandLabel(Command command);
// Its label where −/+ and Space mean something of `mode` ("Zoom in", "Thicker", "Cut").
Bilingual commandLabelIn(Command command, Mode mode);
// The mode's name, "Camera" / "相机".
Bilingual modeLabel(Mode mode);
// Why a key does nothing in `mode`: "R acts in Camera mode (key 1) / R 仅在相机模式下有效（按 1）".
std::string refusalText(Command command, Mode mode);

// The help overlay (H or ?): one line per key, grouped as global keys and each mode's keys, in
// both languages; `visitor` leaves out the operator's commands.
struct HelpSection {
  Bilingual title;
  std::vector<std::string> lines;  // "Ctrl+Z\tUndo / 撤销": the key, a tab, the label
};
std::vector<HelpSection> helpSections(bool visitor);

// Every Chinese character the table and the painter's messages use (the font atlas holds them).
std::string commandTableText();

}  // namespace cb
