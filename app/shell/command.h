// What a person can ask the painter to do, whatever the input: a key (keymap.h), a pen side
// button, a tap on the pen menu or a scripted run. Screens act on commands, never on key codes.
// The list follows thesis Appendix A's steps and keys.
#pragma once

#include <optional>
#include <string_view>

namespace cb {

enum class Command {
  kQuit,
  kModeCamera,       // 1
  kModeCanvas,       // 2
  kModePaint,        // 3
  kModeErase,        // 4
  kModeLight,        // 5
  kMenu,             // M, the pen's upper side button
  kNextBrush,        // B
  kNextMapping,      // N, and the menu (hybrid <-> ray-marching)
  kResetCamera,      // R
  kViewTop,          // Up
  kViewFront,        // Down
  kViewLeft,         // Left
  kViewPerspective,  // Right
  kSpace,            // Vacuum cut in Erase mode; pause the auto-rotation elsewhere
  kSmaller,          // − : vacuum / rub-out diameter, canvas thickness in Canvas mode
  kLarger,           // +
  kBrushSmaller,     // [ , the mouse wheel towards the user, the menu's "Brush −"
  kBrushLarger,      // ] , the wheel away, "Brush +"
  kRaise,            // PageUp: canvas altitude up (Canvas mode)
  kLower,            // PageDown
  kNextEraseTool,    // V: vacuum <-> rub-out
  kToggleCircles,    // C
  kToggleStats,      // S
  kDeleteAll,        // Delete
  kUndo,             // Ctrl+Z
  kRedo,             // Ctrl+Y (and Ctrl+Shift+Z)
  kSave,             // Ctrl+S
  kGoodView,         // G: the nearest view that is not edge-on to the canvas
  kOpen,             // Ctrl+O: open the last saved cloud (--open FILE opens any)
  kNextStyle,        // T: the next render style (thesis, physical, ink, cartoon, sketch)
  // The study operator's (app/shell/study/study_run_screen.h): Ctrl+Alt so a participant's shortcut
  // never triggers one by accident (Ctrl+S is the participant's save).
  kOperatorPause,   // Ctrl+Alt+P: pause (again: resume), with a reason
  kOperatorSkip,    // Ctrl+Alt+S: skip the tutorial step or the stage, with a reason
  kOperatorAbort,   // Ctrl+Alt+A: abort the session, with a reason
  kPanDrag,         // P: a pen drag in Camera mode pans instead of orbiting (and back)
  kPanLeft,         // Shift+Left: move the view left (Camera mode)
  kPanRight,        // Shift+Right
  kPanUp,           // Shift+Up
  kPanDown,         // Shift+Down
  kMorph,           // F: morph the cloud into a saved cloud (animation_preview.h)
  kWind,            // W: start / stop the wind
  kWindDirection,   // D: turn the wind (eight compass directions)
  kApplyAnimation,  // A: apply the morph or wind shown (one undo step)
  kLeaveAnimation,  // X: leave the morph or wind without applying
  kHelp,            // H or ?: the keys of every mode on screen (and again: hidden)
  kCount
};

// "mode-camera", "undo", ... (for logs, the menu and tests).
const char* commandName(Command command);
std::optional<Command> parseCommandName(std::string_view name);

}  // namespace cb
