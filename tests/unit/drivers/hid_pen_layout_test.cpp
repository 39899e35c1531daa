#include "drivers/hid/hid_pen_layout.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/unit/drivers/fixtures.h"

namespace cb::hid {
namespace {

PenLayout layoutOf(const std::string& fixture) {
  const auto bytes = test::readFixture(fixture);
  ParseResult r = parseReportDescriptor(bytes.data(), bytes.size());
  EXPECT_TRUE(r.descriptor) << r.error;
  if (!r.descriptor) return {};
  PenLayoutResult l = findPenLayout(*r.descriptor);
  EXPECT_TRUE(l.layout) << l.error;
  return l.layout.value_or(PenLayout{});
}

TEST(HidPenLayout, FindsThePenInEveryFixture) {
  for (const std::string& name : test::wacomFixtures()) {
    SCOPED_TRACE(name);
    PenLayout l = layoutOf(name);
    EXPECT_EQ(l.report_id, 16);
    EXPECT_EQ(l.report_bytes, 27u);
    for (const FieldSlot* s :
         {&l.x, &l.y, &l.pressure, &l.tilt_x, &l.tilt_y, &l.distance, &l.tip, &l.barrel, &l.barrel2,
          &l.eraser, &l.invert, &l.in_range, &l.sense, &l.serial, &l.serial_high, &l.tool_type})
      EXPECT_TRUE(s->present);
    EXPECT_EQ(l.mode_report_id, 2);
  }
}

TEST(HidPenLayout, Pth660MatchesTheFixtureReadme) {
  // fixtures/hid/README.md: flags byte, X 24 bit 0..44800, Y 24 bit 0..29600, pressure 16 bit
  // 0..8191, tilts 8 bit signed -64..63, distance 0x0132 8 bit, serial 32+32, tool type 16.
  PenLayout l = layoutOf("wacom-pth660_v145.rdesc");
  EXPECT_EQ(l.tip.bit_offset, 0u);
  EXPECT_EQ(l.in_range.bit_offset, 5u);
  EXPECT_EQ(l.sense.bit_offset, 6u);
  EXPECT_EQ(l.x.bit_offset, 8u);
  EXPECT_EQ(l.x.bit_size, 24u);
  EXPECT_EQ(l.x.logical_max, 44800);
  EXPECT_EQ(l.y.logical_max, 29600);
  EXPECT_EQ(l.pressure.bit_size, 16u);
  EXPECT_EQ(l.pressure.logical_max, 8191);
  EXPECT_EQ(l.tilt_x.bit_size, 8u);
  EXPECT_TRUE(l.tilt_x.is_signed);
  EXPECT_EQ(l.distance.logical_max, 63);
  EXPECT_EQ(l.serial.bit_size, 32u);
  EXPECT_EQ(l.serial_high.bit_offset, l.serial.bit_offset + 32);
  EXPECT_EQ(l.tool_type.bit_size, 16u);
}

TEST(HidPenLayout, KernelResolutionRules) {
  PenLayout l = layoutOf("wacom-pth660_v145.rdesc");
  // X: 44800 units over 22.400 cm (exponent -3) = 200 units/mm, as evdev reports.
  EXPECT_EQ(kernelResolution(l.x, false), 200);
  // Tilt: 127 units over 127 degrees = 57.3 units/radian, the kernel rounds to 57.
  EXPECT_EQ(kernelResolution(l.tilt_x, true), 57);
  FieldSlot inches;
  inches.logical_max = 1000;
  inches.physical_max = 10;  // 1000 units over 10 inches = 100 per inch
  inches.unit = 0x13;
  EXPECT_EQ(kernelResolution(inches, false), 4);  // 100 / 25.4 = 3.94 -> 4 units/mm
  FieldSlot none = inches;
  none.unit = 0;
  EXPECT_EQ(kernelResolution(none, false), 0) << "no unit, no resolution";
  PenDeviceInfo d = penDeviceInfo(l, 0x056A, 0x0357, "PTH-660");
  EXPECT_DOUBLE_EQ(d.x_res, 200.0);
  EXPECT_NEAR(d.tilt_res, 57 * M_PI / 180.0, 1e-12);
  EXPECT_EQ(d.pressure_max, 8191);
  EXPECT_EQ(d.distance_max, 63);
}

TEST(HidPenLayout, WacomVendorUsagesMapToDigitizerEquivalents) {
  EXPECT_EQ(equivalentUsage(usage(page::kWacomVendor, 0x42)), pen_usage::kTipSwitch);
  EXPECT_EQ(equivalentUsage(usage(page::kWacomVendor, 0x130)), pen_usage::kX);
  EXPECT_EQ(equivalentUsage(pen_usage::kWacomSense), pen_usage::kWacomSense);
  EXPECT_EQ(equivalentUsage(pen_usage::kWacomDistance), pen_usage::kWacomDistance);
  EXPECT_EQ(equivalentUsage(usage(page::kGenericDesktop, 0x30)), pen_usage::kX);
}

TEST(HidPenLayout, NoPenInAMouseDescriptor) {
  const std::vector<uint8_t> mouse = {0x05, 0x01, 0x09, 0x02, 0xA1, 0x01, 0x09,
                                      0x30, 0x09, 0x31, 0x15, 0x81, 0x25, 0x7F,
                                      0x75, 0x08, 0x95, 0x02, 0x81, 0x06, 0xC0};
  ParseResult r = parseReportDescriptor(mouse.data(), mouse.size());
  ASSERT_TRUE(r.descriptor);
  PenLayoutResult l = findPenLayout(*r.descriptor);
  EXPECT_FALSE(l.layout);
  EXPECT_NE(l.error.find("no input field inside a Stylus"), std::string::npos) << l.error;
}

}  // namespace
}  // namespace cb::hid
