#include "tests/hil/tablet/pen_script.h"

#include "drivers/core/pen_units.h"

namespace cb::hil {

std::vector<PenStep> penScript(int32_t x_max, int32_t y_max, int32_t pressure_max,
                               int32_t distance_max) {
  std::vector<PenStep> steps;
  const uint32_t kSerial = 0x0BADC0DE, kPen = 0x802, kEraser = kScriptEraserToolId;
  PenStep s;
  s.serial = kSerial;
  s.tool_type = kPen;
  // Hover in from the edge of proximity, moving towards the centre.
  for (int i = 0; i < 4; ++i) {
    s.x = x_max / 8 + i * (x_max / 16);
    s.y = y_max / 8 + i * (y_max / 16);
    s.distance = distance_max - i * (distance_max / 4);
    steps.push_back(s);
  }
  // Touch down, then a pressure ramp to the maximum and back while drawing a line.
  s.distance = 0;
  s.tip = true;
  for (int i = 0; i <= 8; ++i) {
    s.pressure = i == 0 ? 20 : (pressure_max * i) / 8;
    s.x += x_max / 40;
    s.y += y_max / 60;
    steps.push_back(s);
  }
  // Tilt sweep across both full ranges (-64..63), pressing lightly.
  s.pressure = pressure_max / 3;
  for (int i = 0; i <= 8; ++i) {
    s.tilt_x = -64 + (127 * i) / 8;
    s.tilt_y = 63 - (127 * i) / 8;
    s.x -= x_max / 50;
    steps.push_back(s);
  }
  // Barrel buttons while drawing, then lift and hover.
  s.barrel = true;
  s.x += 11;
  steps.push_back(s);
  s.barrel = false;
  s.barrel2 = true;
  s.x += 11;
  steps.push_back(s);
  s.barrel2 = false;
  s.tip = false;
  s.pressure = 0;
  s.distance = distance_max / 2;
  s.tilt_x = s.tilt_y = 0;
  steps.push_back(s);
  // Proximity out (the stroke ends).
  PenStep out = s;
  out.in_range = out.sense = false;
  steps.push_back(out);
  // The eraser end: hover in inverted, rub, leave.
  PenStep e;
  e.serial = kSerial;
  e.tool_type = kEraser;
  e.invert = true;
  e.x = x_max / 2;
  e.y = y_max / 2;
  e.distance = distance_max / 3;
  steps.push_back(e);
  e.distance = 0;
  e.eraser = true;
  for (int i = 1; i <= 3; ++i) {
    e.pressure = pressure_max * i / 4;
    e.x += x_max / 30;
    steps.push_back(e);
  }
  e.eraser = false;
  e.pressure = 0;
  e.distance = distance_max / 3;
  steps.push_back(e);
  e.in_range = e.sense = false;
  steps.push_back(e);
  return steps;
}

bool expectedSample(const PenStep& s, const PenDeviceInfo& info, bool intuos4, PenSample& previous,
                    PenSample& out) {
  if (!s.sense) {
    if (!previous.in_proximity) return false;
    out = proximityOutSample(previous, 0);
    previous = out;
    return true;
  }
  PenSample e;
  e.x_raw = s.x;
  e.y_raw = s.y;
  e.pressure_raw = s.pressure;
  e.tilt_x_raw = s.tilt_x;
  e.tilt_y_raw = s.tilt_y;
  e.distance_raw = s.distance;
  // Contact: the tip or eraser switch; the Intuos4 protocol has no switch, the kernel calls
  // pressure above 10 a touch.
  const bool contact = intuos4 ? s.pressure > 10 : (s.tip || s.eraser);
  if (contact) e.buttons |= kPenTip;
  if (s.barrel) e.buttons |= kPenStylus1;
  if (s.barrel2) e.buttons |= kPenStylus2;
  e.tool = (s.invert || s.tool_type == kScriptEraserToolId) ? PenTool::kEraser : PenTool::kPen;
  e.tool_id = s.tool_type;
  e.tool_serial = s.serial;
  e.in_proximity = true;
  convertPenUnits(e, info);
  previous = out = e;
  return true;
}

}  // namespace cb::hil
