// Keys → commands: the one place that decides what a key means (the platform layer only reports
// keysyms and modifiers, app/render/gl/display.h). Letters match case-insensitively, so Shift
// does not change a command (except Ctrl+Shift+Z = redo, and Shift+arrows, which pan).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/render/gl/display.h"
#include "app/shell/command.h"

namespace cb {

std::optional<Command> commandForKey(uint32_t keysym, uint32_t modifiers);
// The command of a display event: a key's, or kQuit for a window close; nullopt otherwise.
std::optional<Command> commandFor(const DisplayEvent& event);

// Key names of scripted runs (`--keys`) and tests: a comma-separated list of keys such as
// "3,b,ctrl+z,space,delete,up" (names: a–z, 0–9, space, esc, enter, delete, up, down, left, right,
// minus, plus, pageup, pagedown, f1–f12; prefixes ctrl+, shift+, alt+). A list without commas whose
// characters are all letters or digits, and which is not one key's name, is read one key per
// character ("bm" = b, m; "delete" = Delete).
bool parseKeyList(std::string_view text, std::vector<DisplayEvent>* keys, std::string* error);

// The keys that give `command` (for the menu's labels), e.g. "Ctrl+Z"; empty when none.
std::string keyLabel(Command command);

}  // namespace cb
