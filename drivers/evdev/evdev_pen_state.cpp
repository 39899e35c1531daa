#include "drivers/evdev/evdev_pen_state.h"

#include "drivers/core/pen_units.h"

namespace cb {

void EvdevPenState::setAbs(uint16_t code, int32_t v) {
  switch (code) {
    case ABS_X:
      x_ = v;
      break;
    case ABS_Y:
      y_ = v;
      break;
    case ABS_PRESSURE:
      pressure_ = v;
      break;
    case ABS_TILT_X:
      tilt_x_ = v;
      break;
    case ABS_TILT_Y:
      tilt_y_ = v;
      break;
    case ABS_DISTANCE:
      distance_ = v;
      break;
    case ABS_MISC:
      misc_ = v;
      break;
    default:
      break;
  }
}

void EvdevPenState::setKey(uint16_t code, bool down) {
  switch (code) {
    case BTN_TOUCH:
      touch_ = down;
      break;
    case BTN_STYLUS:
      stylus_ = down;
      break;
    case BTN_STYLUS2:
      stylus2_ = down;
      break;
    // Pencil, brush and airbrush are pens to a painter; each key is tracked on its own.
    case BTN_TOOL_PEN:
    case BTN_TOOL_PENCIL:
    case BTN_TOOL_BRUSH:
    case BTN_TOOL_AIRBRUSH: {
      const uint32_t bit = 1u << (code - BTN_TOOL_PEN);
      pen_tools_ = down ? (pen_tools_ | bit) : (pen_tools_ & ~bit);
      break;
    }
    case BTN_TOOL_RUBBER:
      tool_rubber_ = down;
      break;
    default:
      break;
  }
}

bool EvdevPenState::feed(const input_event& ev, PenSample& out) {
  switch (ev.type) {
    case EV_ABS:
      setAbs(ev.code, ev.value);
      return false;
    case EV_KEY:
      setKey(ev.code, ev.value != 0);
      return false;
    case EV_MSC:
      if (ev.code == MSC_SERIAL) serial_ = static_cast<uint32_t>(ev.value);
      return false;
    case EV_SYN:
      break;
    default:
      return false;
  }
  if (ev.code != SYN_REPORT) return false;
  const int64_t t_ns =
      int64_t{ev.input_event_sec} * 1000000000 + int64_t{ev.input_event_usec} * 1000;
  const bool in_prox = pen_tools_ != 0 || tool_rubber_;
  if (!in_prox) {
    if (!last_.in_proximity) return false;
    // The leaving frame resets the axes; the stroke ends where the pen was.
    last_ = out = proximityOutSample(last_, t_ns);
    return true;
  }
  PenSample s;
  s.t_ns = t_ns;
  s.x_raw = x_;
  s.y_raw = y_;
  s.pressure_raw = pressure_;
  s.tilt_x_raw = tilt_x_;
  s.tilt_y_raw = tilt_y_;
  s.distance_raw = distance_;
  if (touch_) s.buttons |= kPenTip;
  if (stylus_) s.buttons |= kPenStylus1;
  if (stylus2_) s.buttons |= kPenStylus2;
  s.tool = tool_rubber_ ? PenTool::kEraser : PenTool::kPen;
  s.tool_id = static_cast<uint32_t>(misc_);
  s.tool_serial = serial_;
  s.in_proximity = true;
  convertPenUnits(s, info_);
  last_ = out = s;
  return true;
}

bool EvdevPenState::disconnect(int64_t t_ns, PenSample& out) {
  pen_tools_ = 0;
  tool_rubber_ = touch_ = stylus_ = stylus2_ = false;
  if (!last_.in_proximity) return false;
  last_ = out = proximityOutSample(last_, t_ns);
  return true;
}

}  // namespace cb
