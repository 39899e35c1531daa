#include "drivers/hid/input_fuzz_filter.h"

#include "drivers/core/pen_units.h"

namespace cb::hid {

int32_t defuzzAbsValue(int32_t value, int32_t old_val, int32_t fuzz) {
  // drivers/input/input.c, input_defuzz_abs_event() (Linux 6.1), in 64 bits against overflow.
  const int64_t v = value, o = old_val, f = fuzz;
  if (f) {
    if (v > o - f / 2 && v < o + f / 2) return old_val;
    if (v > o - f && v < o + f) return static_cast<int32_t>((o * 3 + v) / 4);
    if (v > o - f * 2 && v < o + f * 2) return static_cast<int32_t>((o + v) / 2);
  }
  return value;
}

void InputFuzzFilter::apply(PenSample& s, const PenDeviceInfo& info) {
  if (!fuzz_.any()) return;
  if (!s.in_proximity) {  // the leaving frame: what evdev holds, no new values
    if (seeded_) {
      s.x_raw = x_;
      s.y_raw = y_;
      s.tilt_x_raw = tilt_x_;
      s.tilt_y_raw = tilt_y_;
      s.distance_raw = distance_;
      convertPenUnits(s, info);
    }
    if (reset_on_leave_) seeded_ = false;
    return;
  }
  if (!seeded_) {
    seeded_ = true;
  } else {
    s.x_raw = defuzzAbsValue(s.x_raw, x_, fuzz_.position);
    s.y_raw = defuzzAbsValue(s.y_raw, y_, fuzz_.position);
    s.tilt_x_raw = defuzzAbsValue(s.tilt_x_raw, tilt_x_, fuzz_.tilt);
    s.tilt_y_raw = defuzzAbsValue(s.tilt_y_raw, tilt_y_, fuzz_.tilt);
    s.distance_raw = defuzzAbsValue(s.distance_raw, distance_, fuzz_.distance);
    s.pressure_raw = defuzzAbsValue(s.pressure_raw, pressure_, fuzz_.pressure);
  }
  x_ = s.x_raw;
  y_ = s.y_raw;
  tilt_x_ = s.tilt_x_raw;
  tilt_y_ = s.tilt_y_raw;
  distance_ = s.distance_raw;
  pressure_ = s.pressure_raw;
  convertPenUnits(s, info);
}

}  // namespace cb::hid
