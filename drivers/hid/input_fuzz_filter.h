// The input core's fuzz filter, for the backends that bypass it (hidraw, libusb): evdev
// delivers ABS values after drivers/input/input.c input_defuzz_abs_event() has smoothed them
// with the fuzz the kernel driver declared (config/devices: [family.fuzz]), and drops an event
// whose value did not change. With the same fuzz, hidraw/libusb samples equal evdev's:
//
//   |new - old| <  fuzz/2     -> old                      (dropped)
//   |new - old| <  fuzz       -> (3*old + new) / 4
//   |new - old| <  2*fuzz     -> (old + new) / 2
//   otherwise                 -> new
//
// (C integer division, truncating towards zero; fuzz 0 passes every value.) Like absinfo's
// value, `old` is the last value delivered. A proximity-out sample carries the values evdev
// holds. The Intuos protocol's exit packet makes the kernel report 0 on every axis
// (wacom_intuos_inout), so after it the next value passes unfiltered: `reset_on_leave`.
#pragma once

#include <cstdint>

#include "drivers/core/pen_sample.h"
#include "drivers/devices/device_entry.h"

namespace cb::hid {

// input_defuzz_abs_event() for one value.
int32_t defuzzAbsValue(int32_t value, int32_t old_value, int32_t fuzz);

class InputFuzzFilter {
 public:
  explicit InputFuzzFilter(const AxisFuzz& fuzz = {}, bool reset_on_leave = false)
      : fuzz_(fuzz), reset_on_leave_(reset_on_leave) {}
  // Filters the raw axes of `s` in place (X/Y position, tilt, distance, pressure) and
  // recomputes its physical units from `info`.
  void apply(PenSample& s, const PenDeviceInfo& info);
  const AxisFuzz& fuzz() const { return fuzz_; }

 private:
  AxisFuzz fuzz_;
  bool reset_on_leave_ = false;
  bool seeded_ = false;  // the first value passes (absinfo starts at 0 for a device just bound)
  int32_t x_ = 0, y_ = 0, tilt_x_ = 0, tilt_y_ = 0, distance_ = 0, pressure_ = 0;
};

}  // namespace cb::hid
