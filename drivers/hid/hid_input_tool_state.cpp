#include "drivers/hid/hid_input_tool_state.h"

namespace cb::hid {

// hid_report_release_tool(): only a tool that is down is released, together with BTN_TOUCH.
void HidInputToolState::releaseTool(PenTool t) {
  if (t == PenTool::kNone || tool_ != t) return;
  tool_ = PenTool::kNone;
  touch_ = false;
  released_ = true;
}

// hid_report_set_tool(): a different tool is released first.
void HidInputToolState::setTool(PenTool t) {
  if (tool_ != t) releaseTool(tool_);
  tool_ = t;
}

bool HidInputToolState::update(const PenStateValues& v) {
  released_ = false;
  bool active = false;  // report->tool_active
  if (usages_.eraser) {
    active |= v.eraser;
    if (v.eraser) {
      setTool(PenTool::kEraser);
      touch_ = true;
    } else if (tool_ != PenTool::kEraser) {
      // value off, tool not the rubber: ignored
    } else if (!usages_.invert && !touch_) {
      releaseTool(PenTool::kEraser);  // HID_QUIRK_NOINVERT: nothing else would release it
    } else {
      touch_ = false;
    }
  }
  if (usages_.invert) {
    active |= v.invert;
    if (v.invert)
      setTool(PenTool::kEraser);
    else if (!active)
      releaseTool(PenTool::kEraser);
  }
  if (usages_.tip) {
    active |= v.tip;
    if (tool_ != PenTool::kEraser) touch_ = v.tip;
  }
  if (usages_.pressure && !usages_.tip && !usages_.other_touch) {  // HID_QUIRK_NOTOUCH
    // a + ((b - a) >> 3), in the kernel's wrapping 32-bit int arithmetic.
    const auto span = static_cast<int32_t>(static_cast<uint32_t>(pressure_max_) -
                                           static_cast<uint32_t>(pressure_min_));
    const auto threshold = static_cast<int32_t>(static_cast<uint32_t>(pressure_min_) +
                                                static_cast<uint32_t>(span >> 3));
    if (v.pressure > threshold) {
      touch_ = true;
      active = true;
    }
  }
  if (usages_.in_range) {
    active |= v.in_range;
    if (active)
      setTool(tool_ == PenTool::kNone ? PenTool::kPen : tool_);
    else
      releaseTool(PenTool::kPen);
  } else if (active) {
    setTool(tool_ == PenTool::kNone ? PenTool::kPen : tool_);
  } else {
    releaseTool(tool_);
  }
  return released_;
}

}  // namespace cb::hid
