// What the painter says to a person on screen, in English and Chinese (the menu's languages):
// the first screen's hint until the first stroke, the input named honestly, and the answers to
// actions (a save, a cleared cloud, a quit that would lose work). One table, so the font atlas
// holds every character (painterMessagesText) and tests read the same words.
#pragma once

#include <string>
#include <vector>

#include "app/shell/command_table.h"

namespace cb {

namespace msg {
// The first screen (thesis Appendix A: the participant is told how to paint before anything).
inline constexpr Bilingual kHowToPaint{"Press and drag to paint a cloud - lift to see it",
                                       "按住并拖动来画一朵云，松开就能看到"};
inline constexpr Bilingual kPressThreeToPaint{"Press 3 for Paint mode, then press and drag",
                                              "按 3 进入绘画模式，然后按住拖动"};
inline constexpr Bilingual kMousePaints{"No tablet: the mouse is the brush (-/+ pressure)",
                                        "未连接数位板：鼠标就是画笔（-/+ 调压力）"};
inline constexpr Bilingual kPenPaints{"Paint with the pen on the tablet", "用数位笔在数位板上画"};
inline constexpr Bilingual kHelpKey{"H: all keys", "H：全部按键"};
inline constexpr Bilingual kNoSession{"No tablet: the bundled cloud orbits; connect a pen to paint",
                                      "未连接数位板：示例云在旋转；接上数位笔即可绘画"};
// Answers to actions.
inline constexpr Bilingual kSavedAs{"Saved as", "已保存为"};
inline constexpr Bilingual kSaveFailed{"Not saved", "未能保存"};
inline constexpr Bilingual kCleared{"Cloud cleared - Ctrl+Z brings it back",
                                    "云已清除 - 按 Ctrl+Z 可以恢复"};
inline constexpr Bilingual kQuitAsk{"Unsaved cloud: press Esc again or Y to quit, Ctrl+S saves",
                                    "云尚未保存：再按 Esc 或 Y 退出，Ctrl+S 保存"};
inline constexpr Bilingual kForOperator{"That key is for the operator", "该按键仅供操作员使用"};
inline constexpr Bilingual kRotating{"Auto-rotation on - Space stops it",
                                     "自动旋转已开启 - 按空格停止"};
inline constexpr Bilingual kRotationStopped{"Auto-rotation stopped", "自动旋转已停止"};
inline constexpr Bilingual kVacuumPlace{"Vacuum: point at the cloud, then Space cuts",
                                        "吸除：指向云，按空格切除"};
inline constexpr Bilingual kVacuumCut{"Cut - Ctrl+Z brings it back", "已切除 - 按 Ctrl+Z 可以恢复"};
inline constexpr Bilingual kNothingToUndo{"Nothing to undo", "没有可撤销的操作"};
inline constexpr Bilingual kNothingToRedo{"Nothing to redo", "没有可重做的操作"};
// Ink in the veil does not land (PaintSessionSettings::veil_ink_left_out); a session recorded
// before that places it on the mapping's fallback plane through the sky's centre.
inline constexpr Bilingual kInkLeftOut{
    "Ink in the dark veil cannot land and was left out - paint over the grid",
    "暗色遮罩中的墨迹无法落下，已略去 - 请在网格上绘画"};
inline constexpr Bilingual kInkOnFallback{
    "Ink in the veil landed off the canvas, on an upright plane - Ctrl+Z takes it back",
    "遮罩中的墨迹落在画布外的竖直平面上 - 按 Ctrl+Z 撤回"};
inline constexpr Bilingual kStrokeEnded{"Stroke ended (held still 2 s) - lift to go on",
                                        "笔画已结束（静止 2 秒）- 抬起后继续"};
// The statistics panel's rows (hud_items.h appendStatsPanel).
inline constexpr Bilingual kStatsHistogram{"ray samples per pixel (histogram)",
                                           "每像素光线采样（直方图）"};
inline constexpr Bilingual kStatsTotal{"total samples", "采样总数"};
inline constexpr Bilingual kStatsMean{"mean per pixel", "每像素平均"};
inline constexpr Bilingual kStatsMax{"max per pixel", "每像素最大"};
}  // namespace msg

// Every Chinese character of the messages above (for the font atlas).
std::string painterMessagesText();

// The first screen's hint, English over Chinese: how to paint (in Paint mode, else how to get
// there), then the input named honestly (the tablet's pen, else the mouse) with the help key.
std::vector<std::string> firstScreenHint(bool paint_mode, bool tablet);

}  // namespace cb
