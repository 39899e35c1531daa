// The pen motion every in-the-loop test injects (hover, touch, pressure ramp, tilt sweep,
// buttons, eraser, proximity out), the reports that carry it for a descriptor-described pen
// (PTH-660) and for the Intuos4 protocol, and the PenSamples it must come out as.
#pragma once

#include <cstdint>
#include <vector>

#include "drivers/core/pen_sample.h"
#include "drivers/hid/hid_pen_layout.h"

namespace cb::hil {

struct PenStep {
  bool in_range = true, sense = true, tip = false, barrel = false, barrel2 = false;
  bool eraser = false, invert = false;
  int32_t x = 0, y = 0, pressure = 0, tilt_x = 0, tilt_y = 0, distance = 0;
  uint32_t serial = 0, tool_type = 0;
};

// Steps spanning the full ranges of a pen with the given maxima.
std::vector<PenStep> penScript(int32_t x_max, int32_t y_max, int32_t pressure_max,
                               int32_t distance_max);

// Generic HID pen report for a layout (ID byte first when numbered).
std::vector<uint8_t> encodePenReport(const hid::PenLayout& layout, const PenStep& step);

// Intuos4 packets: tool entering proximity, a general pen packet, leaving proximity.
std::vector<uint8_t> encodeIntuos4Enter(uint32_t tool_id, uint32_t serial);
std::vector<uint8_t> encodeIntuos4Pen(const PenStep& step);
std::vector<uint8_t> encodeIntuos4Exit();

// What a backend must report for a step, computed from the script (not from a decoder):
// returns false when the step yields no sample (pen stays out of proximity).
bool expectedSample(const PenStep& step, const PenDeviceInfo& info, bool intuos4,
                    PenSample& previous, PenSample& out);

}  // namespace cb::hil
