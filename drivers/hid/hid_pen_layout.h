// Finds the pen report in a parsed HID report descriptor and where each pen field sits in it,
// for standard digitizers (HID Usage Tables §16, Digitizer page 0x0D) and Wacom's vendor page
// 0xFF0D, whose usages mirror the Digitizer page (plus X/Y at 0x130/0x131, distance at 0x132,
// a proximity "sense" bit at 0x36, serial high word at 0x5C, tool type at 0x77).
//
// Like the kernel's hid-input (drivers/hid/hid-input.c, hidinput_configure_usage), a pen is
// found by its usages, not by the application collection it sits in: any input report with X, Y
// and a stylus state bit (Tip Switch, In Range, Invert or Eraser) inside a Stylus, Pen or
// Digitizer collection of any kind (application, physical or logical) and not inside a Finger
// or Puck collection. Tip pressure is optional (tip-switch-only pens).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "drivers/core/pen_sample.h"
#include "drivers/hid/hid_report_descriptor.h"

namespace cb::hid {

// Pen usages after Wacom's vendor usages are mapped onto their standard equivalents.
namespace pen_usage {
inline constexpr uint32_t kX = usage(page::kGenericDesktop, 0x30);
inline constexpr uint32_t kY = usage(page::kGenericDesktop, 0x31);
inline constexpr uint32_t kZ = usage(page::kGenericDesktop, 0x32);
inline constexpr uint32_t kDigitizer = usage(page::kDigitizer, 0x01);
inline constexpr uint32_t kPen = usage(page::kDigitizer, 0x02);
inline constexpr uint32_t kStylus = usage(page::kDigitizer, 0x20);
inline constexpr uint32_t kPuck = usage(page::kDigitizer, 0x21);
inline constexpr uint32_t kFinger = usage(page::kDigitizer, 0x22);
inline constexpr uint32_t kTipPressure = usage(page::kDigitizer, 0x30);
inline constexpr uint32_t kInRange = usage(page::kDigitizer, 0x32);
inline constexpr uint32_t kTouch = usage(page::kDigitizer, 0x33);
inline constexpr uint32_t kInvert = usage(page::kDigitizer, 0x3C);
inline constexpr uint32_t kTiltX = usage(page::kDigitizer, 0x3D);
inline constexpr uint32_t kTiltY = usage(page::kDigitizer, 0x3E);
inline constexpr uint32_t kTipSwitch = usage(page::kDigitizer, 0x42);
inline constexpr uint32_t kSecondaryTipSwitch = usage(page::kDigitizer, 0x43);
inline constexpr uint32_t kBarrelSwitch = usage(page::kDigitizer, 0x44);
inline constexpr uint32_t kEraser = usage(page::kDigitizer, 0x45);
inline constexpr uint32_t kTabletPick = usage(page::kDigitizer, 0x46);
inline constexpr uint32_t kSecondaryBarrelSwitch = usage(page::kDigitizer, 0x5A);
inline constexpr uint32_t kToolSerial = usage(page::kDigitizer, 0x5B);
inline constexpr uint32_t kToolSerial2 = usage(page::kDigitizer, 0x6E);
inline constexpr uint32_t kWacomSense = usage(page::kWacomVendor, 0x36);
inline constexpr uint32_t kWacomSerialHigh = usage(page::kWacomVendor, 0x5C);
inline constexpr uint32_t kWacomToolType = usage(page::kWacomVendor, 0x77);
inline constexpr uint32_t kWacomDistance = usage(page::kWacomVendor, 0x132);
}  // namespace pen_usage

// Maps a Wacom vendor usage onto the standard usage the kernel's wacom driver treats it as.
uint32_t equivalentUsage(uint32_t extended_usage);

// Where one value lives in the report payload (after the ID byte).
struct FieldSlot {
  bool present = false;
  uint32_t bit_offset = 0, bit_size = 0;
  bool is_signed = false;
  bool null_state = false;  // out-of-range values mean "no value" (Null State main-item bit)
  int32_t logical_min = 0, logical_max = 0;
  int32_t physical_min = 0, physical_max = 0;
  uint32_t unit = 0;
  int32_t unit_exponent = 0;
};

struct PenLayout {
  uint8_t report_id = 0;    // 0: unnumbered
  size_t report_bytes = 0;  // as it travels, ID byte included
  FieldSlot x, y, pressure, tilt_x, tilt_y, distance;
  FieldSlot tip, barrel, barrel2, eraser, invert, in_range, sense;
  // hid-input maps these onto the same evdev codes as the ones above (docs: the table in
  // drivers/hid/README.md): Tablet Pick -> BTN_STYLUS2 like Secondary Barrel Switch, Touch and
  // Secondary Tip Switch -> BTN_TOUCH like Tip Switch, Generic Desktop Z of a Pen application
  // -> ABS_DISTANCE (Linux 6.18).
  FieldSlot tablet_pick, touch, tip2, z;
  FieldSlot serial, serial_high, tool_type;
  // Feature report that switches a Wacom tablet into its full ("tablet") mode, 0 if none.
  uint8_t mode_report_id = 0;
};

struct PenLayoutResult {
  std::optional<PenLayout> layout;
  std::string error;
};

PenLayoutResult findPenLayout(const ReportDescriptor& desc);

// Axis resolution exactly as the kernel's hidinput_calc_abs_res() (drivers/hid/hid-input.c)
// derives it from the descriptor (HID 1.11 §6.2.2.7 units), so the evdev and HID paths agree to
// the unit: positions in units per mm (from cm or inch), tilts in units per radian (from degrees
// or radians), in the kernel's 32-bit arithmetic (an overflowing step gives 0) rounded to the
// closest. 0 when the descriptor gives no unit or no physical extent.
int32_t kernelResolution(const FieldSlot& slot, bool is_angle);

// Ranges and resolutions of the pen described by a layout (PenDeviceInfo fields in evdev's
// units: tilt_res in units per degree converted from the kernel's units per radian).
PenDeviceInfo penDeviceInfo(const PenLayout& layout, uint16_t vendor, uint16_t product,
                            const char* name);

}  // namespace cb::hid
