#include "tests/hil/tablet/pen_script.h"

#include "drivers/core/pen_units.h"
#include "drivers/hid/wacom_tool.h"

namespace cb::hil {

std::vector<PenStep> penScript(int32_t x_max, int32_t y_max, int32_t pressure_max,
                               int32_t distance_max) {
  std::vector<PenStep> steps;
  const uint32_t kSerial = 0x0BADC0DE, kPen = 0x802, kEraser = 0x80A;
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

namespace {

void putBits(std::vector<uint8_t>& r, size_t base, const hid::FieldSlot& slot, uint32_t value) {
  if (!slot.present) return;
  for (uint32_t i = 0; i < slot.bit_size && i < 32; ++i) {
    const size_t bit = slot.bit_offset + i;
    if ((value >> i) & 1u) r[base + bit / 8] |= static_cast<uint8_t>(1u << (bit % 8));
  }
}

}  // namespace

std::vector<uint8_t> encodePenReport(const hid::PenLayout& l, const PenStep& s) {
  std::vector<uint8_t> r(l.report_bytes, 0);
  size_t base = 0;
  if (l.report_id != 0) {
    r[0] = l.report_id;
    base = 1;
  }
  putBits(r, base, l.in_range, s.in_range);
  putBits(r, base, l.sense, s.sense);
  putBits(r, base, l.tip, s.tip && !s.eraser);
  putBits(r, base, l.eraser, s.eraser);
  putBits(r, base, l.invert, s.invert);
  putBits(r, base, l.barrel, s.barrel);
  putBits(r, base, l.barrel2, s.barrel2);
  putBits(r, base, l.x, static_cast<uint32_t>(s.x));
  putBits(r, base, l.y, static_cast<uint32_t>(s.y));
  putBits(r, base, l.pressure, static_cast<uint32_t>(s.pressure));
  putBits(r, base, l.tilt_x, static_cast<uint32_t>(s.tilt_x));
  putBits(r, base, l.tilt_y, static_cast<uint32_t>(s.tilt_y));
  putBits(r, base, l.distance, static_cast<uint32_t>(s.distance));
  putBits(r, base, l.serial, s.sense ? s.serial : 0);
  putBits(r, base, l.tool_type, s.sense ? s.tool_type : 0);
  return r;
}

std::vector<uint8_t> encodeIntuos4Enter(uint32_t id, uint32_t serial) {
  std::vector<uint8_t> d(10, 0);
  d[0] = 2;
  d[1] = 0xC2;
  d[2] = static_cast<uint8_t>(id >> 4);
  d[3] = static_cast<uint8_t>(((id & 0x0F) << 4) | ((serial >> 28) & 0x0F));
  d[4] = static_cast<uint8_t>(serial >> 20);
  d[5] = static_cast<uint8_t>(serial >> 12);
  d[6] = static_cast<uint8_t>(serial >> 4);
  d[7] = static_cast<uint8_t>(((serial & 0x0F) << 4) | ((id >> 16) & 0x0F));
  d[8] = static_cast<uint8_t>(((id >> 12) & 0x0F) << 4);
  return d;
}

std::vector<uint8_t> encodeIntuos4Pen(const PenStep& s) {
  std::vector<uint8_t> d(10, 0);
  const uint32_t x = static_cast<uint32_t>(s.x), y = static_cast<uint32_t>(s.y);
  const uint32_t p = static_cast<uint32_t>(s.pressure);
  const uint32_t tx = static_cast<uint32_t>(s.tilt_x + 64),
                 ty = static_cast<uint32_t>(s.tilt_y + 64);
  d[0] = 2;
  d[1] = static_cast<uint8_t>(0xE0 | (s.barrel2 ? 4 : 0) | (s.barrel ? 2 : 0) | (p & 1));
  d[2] = static_cast<uint8_t>(x >> 9);
  d[3] = static_cast<uint8_t>(x >> 1);
  d[4] = static_cast<uint8_t>(y >> 9);
  d[5] = static_cast<uint8_t>(y >> 1);
  d[6] = static_cast<uint8_t>(p >> 3);
  d[7] = static_cast<uint8_t>((((p >> 1) & 3) << 6) | ((tx >> 1) & 0x3F));
  d[8] = static_cast<uint8_t>(((tx & 1) << 7) | (ty & 0x7F));
  d[9] = static_cast<uint8_t>((static_cast<uint32_t>(s.distance) << 2) | ((x & 1) << 1) | (y & 1));
  return d;
}

std::vector<uint8_t> encodeIntuos4Exit() {
  std::vector<uint8_t> d(10, 0);
  d[0] = 2;
  d[1] = 0x80;
  return d;
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
  e.tool = (s.invert || hid::wacomToolIsEraser(s.tool_type)) ? PenTool::kEraser : PenTool::kPen;
  e.tool_id = s.tool_type;
  e.tool_serial = s.serial;
  e.in_proximity = true;
  convertPenUnits(e, info);
  previous = out = e;
  return true;
}

}  // namespace cb::hil
