// The inverse of the decoders: builds the raw reports a tablet sends, for emulated devices
// (uhid, USB gadget), benchmarks and tests.
#pragma once

#include <cstdint>
#include <vector>

#include "drivers/hid/hid_pen_layout.h"

namespace cb::hid {

// One pen state in device units, as a tablet would report it.
struct PenReportState {
  bool in_range = true, sense = true, tip = false, barrel = false, barrel2 = false;
  bool eraser = false, invert = false;
  int32_t x = 0, y = 0, pressure = 0, tilt_x = 0, tilt_y = 0, distance = 0;
  uint32_t serial = 0, tool_type = 0;
};

// A report for a descriptor-described pen (ID byte first when numbered).
std::vector<uint8_t> encodePenReport(const PenLayout& layout, const PenReportState& state);

// Intuos4 packets (drivers/hid/intuos4_decoder.h): tool entering proximity, a general pen
// packet, tool leaving proximity.
std::vector<uint8_t> encodeIntuos4Enter(uint32_t tool_id, uint32_t serial);
std::vector<uint8_t> encodeIntuos4Pen(const PenReportState& state);
std::vector<uint8_t> encodeIntuos4Exit();

}  // namespace cb::hid
