#include "app/shell/kiosk/visitor_words.h"

#include "app/shell/painter/painter_messages.h"

namespace cb {
namespace {

// The visitor's menu: the modes a visitor has (canvas and light are the operator's), each
// mode's targets, and the targets of every mode.
struct Target {
  Command command;
  const char* key;
  int mode;  // the mode whose row holds it; -1: the modes' row, -2: the last row
};
constexpr Target kTargets[] = {
    {Command::kModeCamera, "menu_camera", -1},
    {Command::kModePaint, "menu_paint", -1},
    {Command::kModeErase, "menu_erase", -1},
    {Command::kResetCamera, "menu_reset_view", int(Mode::kCamera)},
    {Command::kSpace, "menu_rotate", int(Mode::kCamera)},
    {Command::kSmaller, "menu_zoom_out", int(Mode::kCamera)},
    {Command::kLarger, "menu_zoom_in", int(Mode::kCamera)},
    {Command::kNextBrush, "menu_next_brush", int(Mode::kPaint)},
    {Command::kBrushSmaller, "menu_smaller", int(Mode::kPaint)},
    {Command::kBrushLarger, "menu_larger", int(Mode::kPaint)},
    {Command::kGoodView, "menu_good_view", int(Mode::kPaint)},
    {Command::kNextEraseTool, "menu_next_eraser", int(Mode::kErase)},
    {Command::kSmaller, "menu_smaller", int(Mode::kErase)},
    {Command::kLarger, "menu_larger", int(Mode::kErase)},
    {Command::kSpace, "menu_cut", int(Mode::kErase)},
    {Command::kUndo, "menu_undo", -2},
    {Command::kRedo, "menu_redo", -2},
    {Command::kDeleteAll, "menu_start_again", -2},
    {Command::kHelp, "menu_help", -2},
};

// The painter's answers a visitor is told, in the visitor's words.
struct Answer {
  const Bilingual* painter;
  const char* key;
};
const Answer kAnswers[] = {
    {&msg::kNothingToUndo, "nothing_to_undo"},
    {&msg::kNothingToRedo, "nothing_to_redo"},
    {&msg::kCleared, "cleared"},
    {&msg::kInkLeftOut, "ink_lost"},
    {&msg::kInkOnFallback, "ink_lost"},
    {&msg::kStrokeEnded, "stroke_ended"},
    {&msg::kRotating, "rotating"},
    {&msg::kRotationStopped, "rotation_stopped"},
    {&msg::kVacuumPlace, "vacuum_place"},
    {&msg::kVacuumCut, "vacuum_cut"},
};

const char* statusKey(Mode mode) {
  switch (mode) {
    case Mode::kCamera:
      return "status_camera";
    case Mode::kErase:
      return "status_erase";
    default:
      return "status_paint";
  }
}

}  // namespace

std::string visitorStatus(Mode mode, const VisitorText& text) {
  return text(statusKey(mode));
}

std::vector<VisitorMenuRow> visitorMenu(Mode mode, const VisitorText& text) {
  std::vector<VisitorMenuRow> rows(3);
  for (const Target& t : kTargets) {
    if (t.mode >= 0 && t.mode != int(mode)) continue;
    rows[t.mode == -1 ? 0 : t.mode == -2 ? 2 : 1].emplace_back(t.command, text(t.key));
  }
  return rows;
}

std::string visitorAnswer(const std::string& painter_text, const VisitorText& text) {
  for (const Answer& a : kAnswers)
    if (painter_text == a.painter->oneLine()) return text(a.key);
  return "";
}

std::vector<std::string> visitorHelp(const VisitorText& text) {
  std::vector<std::string> lines;
  const std::string help = text("help");
  for (size_t start = 0; start <= help.size();) {
    const size_t end = help.find('\n', start);
    lines.push_back(help.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return lines;
}

std::vector<std::string> visitorWordKeys() {
  std::vector<std::string> keys = {"status_camera", "status_paint", "status_erase", "menu_button",
                                   "menu_close",    "help",         "edge_on"};
  for (const Target& t : kTargets) keys.push_back(t.key);
  for (const Answer& a : kAnswers) keys.push_back(a.key);
  return keys;
}

}  // namespace cb
