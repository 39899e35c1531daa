// The input core's fuzz filter that hidraw/libusb apply to match evdev
// (drivers/input/input.c, input_defuzz_abs_event(), Linux 6.1).
#include "drivers/hid/input_fuzz_filter.h"

#include <gtest/gtest.h>

#include "drivers/core/pen_units.h"

namespace cb::hid {
namespace {

// fuzz 4 (the wacom driver's X/Y): |d| < 2 dropped, |d| < 4 -> (3*old+new)/4,
// |d| < 8 -> (old+new)/2, else new; C division truncates towards zero.
TEST(InputFuzzFilter, KernelRuleForFuzz4) {
  const int32_t old = 1000;
  EXPECT_EQ(defuzzAbsValue(1000, old, 4), 1000);
  EXPECT_EQ(defuzzAbsValue(1001, old, 4), 1000);  // dropped
  EXPECT_EQ(defuzzAbsValue(999, old, 4), 1000);
  EXPECT_EQ(defuzzAbsValue(1002, old, 4), 1000);  // (3000 + 1002) / 4 = 1000.5 -> 1000
  EXPECT_EQ(defuzzAbsValue(1003, old, 4), 1000);  // 4003 / 4
  EXPECT_EQ(defuzzAbsValue(997, old, 4), 999);    // 3997 / 4 = 999.25
  EXPECT_EQ(defuzzAbsValue(1004, old, 4), 1002);  // (1000 + 1004) / 2
  EXPECT_EQ(defuzzAbsValue(1007, old, 4), 1003);  // 2007 / 2 = 1003.5
  EXPECT_EQ(defuzzAbsValue(993, old, 4), 996);    // 1993 / 2 = 996.5
  EXPECT_EQ(defuzzAbsValue(1008, old, 4), 1008);  // 2*fuzz away: passes
  EXPECT_EQ(defuzzAbsValue(992, old, 4), 992);
  // Truncation towards zero below zero, as C does: (3*(-10) + -12) / 4 = -10.5 -> -10.
  EXPECT_EQ(defuzzAbsValue(-12, -10, 4), -10);
  EXPECT_EQ(defuzzAbsValue(-15, -10, 4), -12);  // -25 / 2 = -12.5 -> -12
}

// fuzz 1 (the Intuos protocol's tilt and distance): nothing is dropped (fuzz/2 = 0); a change
// of one unit becomes the mean.
TEST(InputFuzzFilter, KernelRuleForFuzz1AndZero) {
  EXPECT_EQ(defuzzAbsValue(11, 10, 1), 10);   // 21 / 2
  EXPECT_EQ(defuzzAbsValue(9, 10, 1), 9);     // 19 / 2
  EXPECT_EQ(defuzzAbsValue(-9, -10, 1), -9);  // -19 / 2 = -9.5 -> -9
  EXPECT_EQ(defuzzAbsValue(12, 10, 1), 12);
  for (int d = -3; d <= 3; ++d) EXPECT_EQ(defuzzAbsValue(50 + d, 50, 0), 50 + d);
  // No overflow at the ends of the range.
  EXPECT_EQ(defuzzAbsValue(INT32_MAX, INT32_MAX - 1, 4), INT32_MAX - 1);
}

PenDeviceInfo info() {
  PenDeviceInfo d;
  d.x_max = d.y_max = 44704;
  d.x_res = d.y_res = 200;
  d.pressure_max = 2047;
  d.tilt_min = -64;
  d.tilt_max = 63;
  d.distance_max = 63;
  return d;
}

PenSample at(int32_t x, int32_t y, int32_t p, int32_t tilt, bool in = true) {
  PenSample s;
  s.x_raw = x;
  s.y_raw = y;
  s.pressure_raw = p;
  s.tilt_x_raw = s.tilt_y_raw = tilt;
  s.in_proximity = in;
  return s;
}

// A slow stroke through the filter: the values evdev would deliver, per axis with its own fuzz,
// with the physical units recomputed; pressure (fuzz 0) untouched.
TEST(InputFuzzFilter, SlowStrokeAsEvdevDeliversIt) {
  InputFuzzFilter f(AxisFuzz{4, 1, 1, 0});
  const PenDeviceInfo d = info();
  PenSample s = at(1000, 2000, 100, 10);
  f.apply(s, d);  // first value passes
  EXPECT_EQ(s.x_raw, 1000);
  s = at(1001, 2003, 101, 11);
  f.apply(s, d);
  EXPECT_EQ(s.x_raw, 1000);  // dropped
  EXPECT_EQ(s.y_raw, 2000);  // (6000 + 2003) / 4
  EXPECT_EQ(s.pressure_raw, 101);
  EXPECT_EQ(s.tilt_x_raw, 10);  // (10 + 11) / 2
  EXPECT_DOUBLE_EQ(s.y_mm, 2000 / 200.0);
  s = at(1006, 2006, 102, 12);  // against the delivered (filtered) values 1000, 2000, 10
  f.apply(s, d);
  EXPECT_EQ(s.x_raw, 1003);
  EXPECT_EQ(s.y_raw, 2003);
  EXPECT_EQ(s.tilt_x_raw, 12);
  // The leaving frame holds what evdev holds, and the next entry is filtered against it
  // (descriptor protocol) ...
  s = at(1010, 2010, 0, 20, false);
  f.apply(s, d);
  EXPECT_FALSE(s.in_proximity);
  EXPECT_EQ(s.x_raw, 1003);
  EXPECT_EQ(s.tilt_x_raw, 12);
  s = at(1004, 2004, 50, 12);
  f.apply(s, d);
  EXPECT_EQ(s.x_raw, 1003);
  // ... but after the Intuos protocol's exit (the kernel reports 0 on every axis) it passes.
  InputFuzzFilter intuos(AxisFuzz{4, 1, 1, 0}, /*reset_on_leave=*/true);
  s = at(1000, 2000, 100, 10);
  intuos.apply(s, d);
  s = at(0, 0, 0, 0, false);
  intuos.apply(s, d);
  s = at(1001, 2001, 100, 10);
  intuos.apply(s, d);
  EXPECT_EQ(s.x_raw, 1001);
  // No fuzz: nothing changes.
  InputFuzzFilter none;
  s = at(5, 6, 7, 8);
  none.apply(s, d);
  s = at(6, 6, 7, 8);
  none.apply(s, d);
  EXPECT_EQ(s.x_raw, 6);
}

}  // namespace
}  // namespace cb::hid
