// What the painter says to a kiosk visitor, every word from the kiosk's texts (config/kiosk/
// texts.toml through KioskTexts, in the configured language): the status line per mode, the
// menu's button and targets, the answers to the visitor's actions and the help. The painter's
// own words (keys, brush and mapping names, pressure figures, file paths, the pen's driver
// status) are for the operator and the log: a visitor sees none of them. An answer with no
// visitor text is not shown (it still goes to the log).
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "app/session/ui_change.h"
#include "app/shell/command.h"

namespace cb {

// The kiosk's text of a key (KioskTexts::text).
using VisitorText = std::function<std::string(const std::string& key)>;

// One row of the visitor's menu: each target's command and words.
using VisitorMenuRow = std::vector<std::pair<Command, std::string>>;

// The status line in `mode`.
std::string visitorStatus(Mode mode, const VisitorText& text);
// The menu in `mode`: the modes, the mode's own targets, then undo, redo, start again, help.
std::vector<VisitorMenuRow> visitorMenu(Mode mode, const VisitorText& text);
// The visitor's words for one of the painter's answers (painter_messages.h, oneLine()), or ""
// when it has none (the answer is then not shown).
std::string visitorAnswer(const std::string& painter_text, const VisitorText& text);
// The help's lines.
std::vector<std::string> visitorHelp(const VisitorText& text);
// Every key the above read (each must be in kKioskTextKeys).
std::vector<std::string> visitorWordKeys();

}  // namespace cb
