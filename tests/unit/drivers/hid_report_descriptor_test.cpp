#include "drivers/hid/hid_report_descriptor.h"

#include <gtest/gtest.h>

#include "tests/hil/tablet/intuos4_handbuilt.h"
#include "tests/unit/drivers/fixtures.h"

namespace cb::hid {
namespace {

ParseResult parse(const std::vector<uint8_t>& d) {
  return parseReportDescriptor(d.data(), d.size());
}

TEST(HidReportDescriptor, ParsesEveryWacomFixture) {
  for (const std::string& name : test::wacomFixtures()) {
    SCOPED_TRACE(name);
    const std::vector<uint8_t> bytes = test::readFixture(name);
    ASSERT_GT(bytes.size(), 900u) << "fixture missing";
    ParseResult r = parse(bytes);
    ASSERT_TRUE(r.descriptor) << r.error;
    EXPECT_TRUE(r.descriptor->numbered);
    // Every Intuos Pro sends its pen on report 16: 26 payload bytes + the ID.
    EXPECT_EQ(r.descriptor->reportBytes(ReportType::kInput, 16), 27u);
    EXPECT_GT(r.descriptor->reportBytes(ReportType::kFeature, 2), 0u) << "mode report";
  }
}

TEST(HidReportDescriptor, Pth660PenReportFieldsAndBitOffsets) {
  ParseResult r = parse(test::readFixture("wacom-pth660_v145.rdesc"));
  ASSERT_TRUE(r.descriptor);
  std::vector<const Field*> pen;
  for (const Field& f : r.descriptor->fields)
    if (f.type == ReportType::kInput && f.report_id == 16) pen.push_back(&f);
  ASSERT_GE(pen.size(), 10u);
  // Seven flag bits, one padding bit, then X (24 bits, 0..44800 in cm with exponent -3).
  EXPECT_EQ(pen[0]->count, 7u);
  EXPECT_EQ(pen[0]->usageAt(0), usage(page::kWacomVendor, 0x42));
  EXPECT_TRUE(pen[1]->isConstant());
  EXPECT_EQ(pen[2]->bit_offset, 8u);
  EXPECT_EQ(pen[2]->bit_size, 24u);
  EXPECT_EQ(pen[2]->logical_max, 44800);
  EXPECT_EQ(pen[2]->physical_max, 22400);
  EXPECT_EQ(pen[2]->unit, 0x11u);
  EXPECT_EQ(pen[2]->unit_exponent, -3);
  EXPECT_EQ(pen[2]->application, usage(page::kWacomVendor, 0x01));
  // Tilts are signed 8-bit, -64..63 degrees.
  const Field* tilt = pen[5];
  EXPECT_EQ(tilt->usageAt(0), usage(page::kWacomVendor, 0x3D));
  EXPECT_EQ(tilt->usageAt(1), usage(page::kWacomVendor, 0x3E));
  EXPECT_EQ(tilt->logical_min, -64);
  EXPECT_TRUE(tilt->isSigned());
}

TEST(HidReportDescriptor, HandBuiltIntuos4Descriptor) {
  ParseResult r = parse(hil::handBuiltIntuos4Descriptor());
  ASSERT_TRUE(r.descriptor) << r.error;
  EXPECT_EQ(r.descriptor->reportBytes(ReportType::kInput, 2), 10u);
  EXPECT_EQ(r.descriptor->reportBytes(ReportType::kFeature, 2), 2u);
}

TEST(HidReportDescriptor, PushPopRestoresGlobalState) {
  const std::vector<uint8_t> d = {
      0x05, 0x01, 0x09, 0x02, 0xA1, 0x01,              // GD, Mouse, Application
      0x15, 0x00, 0x25, 0x01, 0x75, 0x01, 0x95, 0x03,  // 0..1, 1 bit x3
      0xA4,                                            // Push
      0x75, 0x08, 0x95, 0x02, 0x15, 0x81, 0x25, 0x7F,  // 8 bits x2, -127..127
      0x09, 0x30, 0x09, 0x31, 0x81, 0x06,              // X, Y relative
      0xB4,                                            // Pop
      0x05, 0x09, 0x19, 0x01, 0x29, 0x03, 0x81, 0x02,  // Buttons 1..3 (1 bit x3 again)
      0xC0};
  ParseResult r = parse(d);
  ASSERT_TRUE(r.descriptor) << r.error;
  ASSERT_EQ(r.descriptor->fields.size(), 2u);
  const Field& xy = r.descriptor->fields[0];
  EXPECT_EQ(xy.bit_size, 8u);
  EXPECT_EQ(xy.logical_min, -127);
  EXPECT_EQ(xy.flags & kFieldRelative, kFieldRelative);
  const Field& buttons = r.descriptor->fields[1];
  EXPECT_EQ(buttons.bit_size, 1u);
  EXPECT_EQ(buttons.count, 3u);
  EXPECT_EQ(buttons.bit_offset, 16u);
  EXPECT_EQ(buttons.logical_max, 1);
  ASSERT_EQ(buttons.usages.size(), 3u);
  EXPECT_EQ(buttons.usages[2], usage(page::kButton, 3));
}

TEST(HidReportDescriptor, UnsignedMaximumWithNonNegativeMinimum) {
  // Logical Maximum 0xFF in one byte means 255 when the minimum is 0.
  const std::vector<uint8_t> d = {0x05, 0x0D, 0x09, 0x02, 0xA1, 0x01, 0x15, 0x00, 0x25, 0xFF,
                                  0x75, 0x08, 0x95, 0x01, 0x09, 0x30, 0x81, 0x02, 0xC0};
  ParseResult r = parse(d);
  ASSERT_TRUE(r.descriptor) << r.error;
  EXPECT_EQ(r.descriptor->fields[0].logical_max, 255);
}

// hid-core.c, fetch_item() + hid_open_report(): an item with tag 15 is a long item and the
// kernel refuses the descriptor on the first one ("unexpected long global item").
TEST(HidReportDescriptor, LongItemsAreRejectedAsLinuxRejectsThem) {
  const std::vector<uint8_t> d = {0x05, 0x0D, 0xFE, 0x02, 0x10, 0xAA, 0xBB,  // long item at 2
                                  0x09, 0x02, 0xA1, 0x01, 0x75, 0x08, 0x95, 0x01, 0x81, 0x02, 0xC0};
  ParseResult r = parse(d);
  EXPECT_FALSE(r.descriptor);
  EXPECT_NE(r.error.find("byte 2: long items"), std::string::npos) << r.error;
}

struct Malformed {
  const char* what;
  std::vector<uint8_t> bytes;
  const char* reason;  // substring of the error
};

TEST(HidReportDescriptor, RejectsMalformedWithAReason) {
  const std::vector<Malformed> cases = {
      {"empty", {}, "empty"},
      {"truncated item", {0x05, 0x0D, 0x26, 0xFF}, "byte 2: item data runs past"},
      {"pop without push", {0xB4}, "pop without push"},
      {"end without collection", {0xC0}, "end collection without"},
      {"unclosed", {0x05, 0x0D, 0x09, 0x02, 0xA1, 0x01}, "open collection"},
      {"report id 0", {0x85, 0x00}, "report ID must be 1..255"},
      {"report size 257", {0xA1, 0x01, 0x76, 0x01, 0x01}, "byte 2: report size 257 is over 256"},
      {"huge count", {0xA1, 0x01, 0x75, 0x08, 0x96, 0xFF, 0xFF}, "report count 65535 is over"},
      {"too long report",
       {0xA1, 0x01, 0x76, 0x00, 0x01, 0x96, 0x00, 0x01, 0x81, 0x02, 0xC0},
       "byte 8: report is longer than 4096 bytes"},
      {"inverted logical range",
       {0xA1, 0x01, 0x15, 0x05, 0x25, 0x01, 0x75, 0x08, 0x95, 0x01, 0x81, 0x02, 0xC0},
       "byte 10: logical maximum 1 is below logical minimum 5"},
      {"unknown global tag", {0xC4}, "unknown global item tag"},
      {"nested delimiters", {0xA9, 0x01, 0xA9, 0x01}, "nested delimiters"},
      {"close delimiter", {0xA9, 0x00}, "close delimiter without"},
      {"open delimiter at end",
       {0xA1, 0x01, 0x75, 0x08, 0x95, 0x01, 0x81, 0x02, 0xC0, 0xA9, 0x01},
       "inside a delimiter"},
      {"inverted usage range", {0x19, 0x05, 0x29, 0x01}, "usage range"},
      {"usage max alone", {0x29, 0x01}, "without usage minimum"},
      {"no fields", {0xA1, 0x01, 0xC0}, "no fields"},
      {"mixed numbering",
       {0xA1, 0x01, 0x75, 0x08, 0x95, 0x01, 0x81, 0x02, 0x85, 0x01, 0xC0},
       "report ID after fields"},
  };
  for (const Malformed& m : cases) {
    SCOPED_TRACE(m.what);
    ParseResult r = parse(m.bytes);
    EXPECT_FALSE(r.descriptor);
    EXPECT_NE(r.error.find(m.reason), std::string::npos) << r.error;
  }
  std::vector<uint8_t> deep;
  for (int i = 0; i < 5; ++i) deep.push_back(0xA4);  // HID_GLOBAL_STACK_SIZE is 4
  EXPECT_NE(parse(deep).error.find("byte 4: push nested too deeply"), std::string::npos);
  std::vector<uint8_t> nested;
  for (int i = 0; i < 40; ++i) nested.insert(nested.end(), {0xA1, 0x00});
  EXPECT_NE(parse(nested).error.find("nested too deeply"), std::string::npos);
  std::vector<uint8_t> big(kMaxDescriptorBytes + 1, 0x00);
  EXPECT_NE(parse(big).error.find("longer than"), std::string::npos);
}

TEST(HidReportDescriptor, ExtractBitsAndSignExtend) {
  const uint8_t p[] = {0xA5, 0x3C, 0xFF};
  EXPECT_EQ(extractBits(p, 3, 0, 8), 0xA5u);
  EXPECT_EQ(extractBits(p, 3, 4, 8), 0xCAu);  // high nibble of byte 0, low nibble of byte 1
  EXPECT_EQ(extractBits(p, 3, 8, 16), 0xFF3Cu);
  EXPECT_EQ(extractBits(p, 3, 12, 8), 0xF3u);
  EXPECT_EQ(extractBits(p, 2, 12, 8), 0x03u) << "bits past the end read as zero";
  EXPECT_EQ(signExtend(0x7F, 7), -1);
  EXPECT_EQ(signExtend(0x40, 7), -64);
  EXPECT_EQ(signExtend(0x3F, 7), 63);
  EXPECT_EQ(signExtend(0xFFFFFFFFu, 32), -1);
}

}  // namespace
}  // namespace cb::hid
