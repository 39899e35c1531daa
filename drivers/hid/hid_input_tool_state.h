// The kernel's generic pen state machine: how hid-input (drivers/hid/hid-input.c,
// hidinput_hid_event with hid_report_set_tool / hid_report_release_tool) turns the Eraser,
// Invert, Tip Switch, Tip Pressure and In Range bits of one report into BTN_TOOL_PEN /
// BTN_TOOL_RUBBER and BTN_TOUCH. The usages are taken in the kernel's priority order
// (hidinput_usages_priorities: Eraser, Invert, Tip Switch, Tip Pressure, In Range).
//
// Notable consequences, all as the kernel does them:
// - Eraser set selects the rubber tool and its value is BTN_TOUCH (the Eraser usage maps to
//   BTN_TOUCH), with or without Invert; a tip switch is ignored while the rubber is the tool.
// - Without an Invert usage in the descriptor (HID_QUIRK_NOINVERT), the rubber is released one
//   report after Eraser and the touch both went to 0.
// - A pen with Tip Pressure but no Tip Switch (HID_QUIRK_NOTOUCH) touches once pressure passes
//   an eighth of its range; the touch lasts until the tool is released.
// - Without an In Range usage nothing selects the pen tool; this decoder then treats the pen as
//   in proximity while it touches (the kernel reports BTN_TOUCH with no tool at all).
#pragma once

#include <cstdint>

#include "drivers/core/pen_sample.h"

namespace cb::hid {

// Which of the state usages the descriptor declares (fixed per device).
struct PenStateUsages {
  bool eraser = false, invert = false, tip = false, pressure = false, in_range = false;
  // Touch or Secondary Tip Switch: they map to BTN_TOUCH too, so no HID_QUIRK_NOTOUCH.
  bool other_touch = false;
};

// One report's values of those usages (pressure already clamped to its logical range).
struct PenStateValues {
  bool eraser = false, invert = false, tip = false, in_range = false;
  int32_t pressure = 0;
};

class HidInputToolState {
 public:
  HidInputToolState(const PenStateUsages& usages, int32_t pressure_min, int32_t pressure_max)
      : usages_(usages), pressure_min_(pressure_min), pressure_max_(pressure_max) {}

  // Processes one report; afterwards tool() and touch() are what evdev shows. Returns true when
  // the kernel released a tool in the middle of this report (it then sends an extra EV_SYN).
  bool update(const PenStateValues& v);
  PenTool tool() const { return tool_; }
  bool touch() const { return touch_; }
  // BTN_TOUCH set by a usage processed after the state usages (Touch, Secondary Tip Switch).
  void setTouch(bool t) { touch_ = t; }
  void reset() { tool_ = PenTool::kNone, touch_ = false; }

 private:
  void setTool(PenTool t);
  void releaseTool(PenTool t);

  PenStateUsages usages_;
  int32_t pressure_min_ = 0, pressure_max_ = 0;
  PenTool tool_ = PenTool::kNone;
  bool touch_ = false;
  bool released_ = false;
};

}  // namespace cb::hid
