// PenSample: the one type that leaves drivers/. Everything downstream (calibration, brushes,
// the journal, replay) is written against it, so it can be fed from a tablet, a recording or a
// synthetic path alike.
#pragma once

#include <cstdint>

namespace cb {

enum class PenTool : uint8_t { kNone = 0, kPen = 1, kEraser = 2 };

// Button bits in PenSample::buttons.
enum PenButton : uint32_t {
  kPenTip = 1u << 0,      // BTN_TOUCH: the nib is in contact (as the device reports it)
  kPenStylus1 = 1u << 1,  // BTN_STYLUS, the lower barrel button
  kPenStylus2 = 1u << 2,  // BTN_STYLUS2, the upper barrel button
};

struct PenSample {
  int64_t t_ns = 0;  // CLOCK_MONOTONIC timestamp of the report (kernel time where available)

  // Position: raw device units and millimetres from the active area's top-left corner.
  int32_t x_raw = 0, y_raw = 0;
  double x_mm = 0.0, y_mm = 0.0;

  // Pressure: raw device units and normalised to 0..1 by the device's maximum.
  int32_t pressure_raw = 0;
  float pressure = 0.0f;

  // Tilt in degrees from vertical, +x to the right, +y towards the user (raw units kept too).
  int32_t tilt_x_raw = 0, tilt_y_raw = 0;
  float tilt_x_deg = 0.0f, tilt_y_deg = 0.0f;

  // Hover distance: raw units and normalised 0 (touching) .. 1 (edge of proximity).
  int32_t distance_raw = 0;
  float distance = 0.0f;

  uint32_t buttons = 0;  // PenButton bits
  PenTool tool = PenTool::kNone;
  uint32_t tool_id = 0;      // Wacom tool id (ABS_MISC), 0 when unknown
  uint64_t tool_serial = 0;  // MSC_SERIAL, 0 when unknown
  bool in_proximity = false;

  bool tipDown() const { return (buttons & kPenTip) != 0; }
};

// Static description of a pen device, needed to interpret raw units.
struct PenDeviceInfo {
  uint16_t usb_vendor = 0, usb_product = 0;
  char name[96] = {};
  int32_t x_max = 0, y_max = 0;     // raw range is 0..max
  double x_res = 0.0, y_res = 0.0;  // units per mm
  int32_t pressure_max = 0;
  int32_t tilt_min = 0, tilt_max = 0;  // raw range
  double tilt_res = 0.0;               // units per degree (0: assume raw = degrees)
  int32_t distance_max = 0;
};

}  // namespace cb
