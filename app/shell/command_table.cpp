#include "app/shell/command_table.h"

#include <iterator>

#include "app/shell/keymap.h"

namespace cb {
namespace {

constexpr unsigned kCamera = modeBit(Mode::kCamera), kCanvas = modeBit(Mode::kCanvas),
                   kErase = modeBit(Mode::kErase), kPaint = modeBit(Mode::kPaint);

struct Row {
  Command command;
  unsigned modes;
  bool operator_only;  // not offered to kiosk visitors (PaintScreen::visitorAllows)
  Bilingual label;
};

// Thesis Appendix A's keys and the painter's additions; where a command acts.
constexpr Row kRows[] = {
    {Command::kQuit, kEveryMode, true, {"Quit", "退出"}},
    {Command::kModeCamera, kEveryMode, false, {"Camera", "相机"}},
    {Command::kModeCanvas, kEveryMode, true, {"Canvas", "画布"}},
    {Command::kModePaint, kEveryMode, false, {"Paint", "绘画"}},
    {Command::kModeErase, kEveryMode, false, {"Erase", "擦除"}},
    {Command::kModeLight, kEveryMode, true, {"Light", "光照"}},
    {Command::kMenu, kEveryMode, false, {"Menu", "菜单"}},
    {Command::kNextBrush, kEveryMode, false, {"Next brush", "换笔刷"}},
    {Command::kNextMapping, kEveryMode, false, {"Mapping", "映射方式"}},
    {Command::kResetCamera, kCamera, false, {"Reset view", "重置视角"}},
    {Command::kViewTop, kCamera, false, {"Top", "俯视"}},
    {Command::kViewFront, kCamera, false, {"Front", "正视"}},
    {Command::kViewLeft, kCamera, false, {"Left", "左视"}},
    {Command::kViewPerspective, kCamera, false, {"3/4 view", "斜视"}},
    {Command::kSpace, kCamera | kErase, false, {"Auto-rotate / Cut", "自动旋转 / 切除"}},
    {Command::kSmaller, kEveryMode, false, {"Smaller", "变小"}},
    {Command::kLarger, kEveryMode, false, {"Larger", "变大"}},
    {Command::kBrushSmaller, kPaint, false, {"Brush -", "笔刷缩小"}},
    {Command::kBrushLarger, kPaint, false, {"Brush +", "笔刷放大"}},
    {Command::kRaise, kCanvas, true, {"Raise", "升高"}},
    {Command::kLower, kCanvas, true, {"Lower", "降低"}},
    {Command::kNextEraseTool, kErase, false, {"Vacuum/rub-out", "吸除/擦拭"}},
    {Command::kToggleCircles, kEveryMode, false, {"Circles", "圆圈"}},
    {Command::kToggleStats, kEveryMode, true, {"Details", "详细信息"}},
    {Command::kDeleteAll, kEveryMode, false, {"Delete all", "全部删除"}},
    {Command::kUndo, kEveryMode, false, {"Undo", "撤销"}},
    {Command::kRedo, kEveryMode, false, {"Redo", "重做"}},
    {Command::kSave, kEveryMode, true, {"Save", "保存"}},
    {Command::kGoodView, kEveryMode, false, {"Good view", "最佳视角"}},
    {Command::kOpen, kEveryMode, true, {"Open last", "打开上次"}},
    {Command::kNextStyle, kEveryMode, true, {"Style", "风格"}},
    {Command::kOperatorPause, kEveryMode, true, {"Pause (operator)", "暂停（操作员）"}},
    {Command::kOperatorSkip, kEveryMode, true, {"Skip (operator)", "跳过（操作员）"}},
    {Command::kOperatorAbort, kEveryMode, true, {"Abort (operator)", "中止（操作员）"}},
    {Command::kPanDrag, kCamera, false, {"Drag pans", "拖动平移"}},
    {Command::kPanLeft, kCamera, false, {"Pan left", "左移"}},
    {Command::kPanRight, kCamera, false, {"Pan right", "右移"}},
    {Command::kPanUp, kCamera, false, {"Pan up", "上移"}},
    {Command::kPanDown, kCamera, false, {"Pan down", "下移"}},
    {Command::kMorph, kEveryMode, true, {"Morph", "变形"}},
    {Command::kWind, kEveryMode, true, {"Wind", "风"}},
    {Command::kWindDirection, kEveryMode, true, {"Wind dir.", "风向"}},
    {Command::kApplyAnimation, kEveryMode, true, {"Apply", "应用"}},
    {Command::kLeaveAnimation, kEveryMode, true, {"Leave", "放弃"}},
    {Command::kHelp, kEveryMode, false, {"Help", "帮助"}},
};
static_assert(std::size(kRows) == size_t(Command::kCount), "one row per command");

constexpr Bilingual kModeLabels[] = {{"Camera", "相机"},
                                     {"Canvas", "画布"},
                                     {"Paint", "绘画"},
                                     {"Erase", "擦除"},
                                     {"Light", "光照"}};

// What −/+ and Space do in each mode (the menu's and the help's words).
struct ModeWord {
  Command command;
  Mode mode;
  Bilingual label;
};
constexpr ModeWord kModeWords[] = {
    {Command::kSmaller, Mode::kCamera, {"Zoom out", "拉远"}},
    {Command::kLarger, Mode::kCamera, {"Zoom in", "拉近"}},
    {Command::kSpace, Mode::kCamera, {"Auto-rotate", "自动旋转"}},
    {Command::kSmaller, Mode::kCanvas, {"Thinner", "变薄"}},
    {Command::kLarger, Mode::kCanvas, {"Thicker", "变厚"}},
    {Command::kSmaller, Mode::kErase, {"Smaller", "变小"}},
    {Command::kLarger, Mode::kErase, {"Larger", "变大"}},
    {Command::kSpace, Mode::kErase, {"Cut", "切除"}},
    {Command::kSmaller, Mode::kLight, {"Warmer", "更暖"}},
    {Command::kLarger, Mode::kLight, {"Cooler", "更冷"}},
};

const Row& row(Command command) {
  return kRows[size_t(command) < std::size(kRows) ? size_t(command) : 0];
}

std::string helpLine(Command command, Bilingual label) {
  std::string key = keyLabel(command);
  if (command == Command::kHelp) key = "H / ?";
  return key + "\t" + label.oneLine();
}

}  // namespace

unsigned commandModes(Command command) {
  return command == Command::kCount ? 0u : row(command).modes;
}

Bilingual commandLabel(Command command) {
  if (command == Command::kCount) return {};
  return row(command).label;
}

Bilingual commandLabelIn(Command command, Mode mode) {
  for (const ModeWord& w : kModeWords)
    if (w.command == command && w.mode == mode) return w.label;
  return commandLabel(command);
}

Bilingual modeLabel(Mode mode) {
  return kModeLabels[int(mode)];
}

std::string refusalText(Command command, Mode mode) {
  const unsigned modes = commandModes(command);
  std::string en = keyLabel(command) + " acts in ", zh = keyLabel(command) + " 仅在";
  bool first = true;
  for (int m = 0; m < 5; ++m) {
    if (!(modes & (1u << unsigned(m)))) continue;
    const std::string key = std::to_string(m + 1);
    en += (first ? "" : " and ") + std::string(kModeLabels[m].en) + " mode (key " + key + ")";
    zh += (first ? "" : "和") + std::string(kModeLabels[m].zh) + "模式（按 " + key + "）";
    first = false;
  }
  en += ", not in " + std::string(kModeLabels[int(mode)].en) + " mode";
  zh += "中有效";
  return en + " / " + zh;
}

std::vector<HelpSection> helpSections(bool visitor) {
  std::vector<HelpSection> sections;
  HelpSection global{{"Every mode", "所有模式"}, {}};
  for (const Row& r : kRows) {
    if (r.modes != kEveryMode || (visitor && r.operator_only)) continue;
    if (r.command == Command::kSmaller || r.command == Command::kLarger) continue;  // per mode
    if (r.command >= Command::kOperatorPause && r.command <= Command::kOperatorAbort) continue;
    global.lines.push_back(helpLine(r.command, r.label));
  }
  sections.push_back(global);
  for (int m = 0; m < 5; ++m) {
    const Mode mode = Mode(m);
    if (visitor && (mode == Mode::kCanvas || mode == Mode::kLight)) continue;
    HelpSection s{kModeLabels[m], {}};
    for (const Row& r : kRows)
      if (r.modes != kEveryMode && (r.modes & modeBit(mode)) && !(visitor && r.operator_only))
        s.lines.push_back(helpLine(r.command, commandLabelIn(r.command, mode)));
    for (const ModeWord& w : kModeWords)
      if (w.mode == mode && w.command != Command::kSpace)
        s.lines.push_back(helpLine(w.command, w.label));
    if (mode == Mode::kPaint)
      s.lines.push_back(helpLine(Command::kCount, {"press and drag: paint, lift: the cloud",
                                                   "按住拖动：绘画，抬起：成云"}));
    sections.push_back(s);
  }
  return sections;
}

std::string commandTableText() {
  std::string text;
  for (const Row& r : kRows) text += r.label.zh;
  for (const ModeWord& w : kModeWords) text += w.label.zh;
  for (const Bilingual& b : kModeLabels) text += b.zh;
  text += "仅在和模式中有效按所有抬起成云";
  return text;
}

}  // namespace cb
