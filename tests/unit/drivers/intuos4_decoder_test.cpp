#include "drivers/hid/intuos4_decoder.h"

#include <gtest/gtest.h>

#include "drivers/core/pen_units.h"
#include "tests/hil/tablet/pen_script.h"
#include "tests/unit/drivers/fixtures.h"

namespace cb::hid {
namespace {

// The Intuos4 6x9 (PTK-640) as config/devices/wacom-intuos4.toml describes it.
PenDeviceInfo info() {
  return test::shippedEntry(0x056A, 0x00B9).info;
}
std::shared_ptr<const ToolTable> tools() {
  return test::shippedEntry(0x056A, 0x00B9).tools;
}

TEST(Intuos4Decoder, ModelsAndRanges) {
  EXPECT_EQ(test::shippedEntry(0x056A, 0x00B9).protocol, PenProtocol::kIntuos4);
  EXPECT_EQ(test::shippedEntry(0x056A, 0x0357).protocol, PenProtocol::kDescriptor);
  EXPECT_EQ(test::shippedDevices().find(0x1234, 0x00B9), nullptr);
  PenDeviceInfo d = info();
  EXPECT_EQ(d.x_max, 44704);
  EXPECT_EQ(d.pressure_max, 2047);  // 11 bits
  EXPECT_EQ(d.distance_max, 63);
}

TEST(Intuos4Decoder, HandAssembledPackets) {
  Intuos4Decoder dec(info(), tools());
  PenSample s;
  // Enter: tool id 0x802 (general pen), serial 0x12345678.
  const uint8_t enter[10] = {0x02, 0xC2, 0x80, 0x21, 0x23, 0x45, 0x67, 0x80, 0x00, 0x00};
  EXPECT_EQ(dec.decode(enter, 10, 1, s).status, DecodeStatus::kNoSample);
  // Pen: X = 0x1234 << 1 | 1, Y = 0x0567 << 1 | 0, distance 5, pressure 0x3FF (bits 10..3 =
  // 0x7F, bits 2..1 = 3, bit 0 = 1), tilt X raw 100 -> 36, tilt Y raw 20 -> -44, barrel 1.
  const uint8_t pen[10] = {0x02, 0xE3, 0x12, 0x34, 0x05, 0x67, 0x7F, 0xF2, 0x14, 0x16};
  ASSERT_EQ(dec.decode(pen, 10, 2, s).status, DecodeStatus::kSample);
  EXPECT_EQ(s.x_raw, 0x2469);
  EXPECT_EQ(s.y_raw, 0x0ACE);
  EXPECT_EQ(s.distance_raw, 5);
  EXPECT_EQ(s.pressure_raw, 0x3FF);
  EXPECT_EQ(s.tilt_x_raw, 36);
  EXPECT_EQ(s.tilt_y_raw, -44);
  EXPECT_EQ(s.buttons, kPenTip | kPenStylus1);
  EXPECT_EQ(s.tool, PenTool::kPen);
  EXPECT_EQ(s.tool_id, 0x802u);
  EXPECT_EQ(s.tool_serial, 0x12345678u);
  EXPECT_TRUE(s.in_proximity);
  EXPECT_DOUBLE_EQ(s.x_mm, 0x2469 / 200.0);
  // Leaving proximity ends the stroke where the pen was.
  const uint8_t exit[10] = {0x02, 0x80};
  ASSERT_EQ(dec.decode(exit, 10, 3, s).status, DecodeStatus::kSample);
  EXPECT_FALSE(s.in_proximity);
  EXPECT_EQ(s.x_raw, 0x2469);
  EXPECT_EQ(s.buttons, 0u);
  // After leaving, pen packets are ignored until a tool enters again.
  DecodeResult r = dec.decode(pen, 10, 4, s);
  EXPECT_EQ(r.status, DecodeStatus::kNoSample);
  EXPECT_NE(r.reason.find("before the tool entered"), std::string::npos);
}

// drivers/hid/wacom_wac.c, wacom_intuos_inout(): the tool id takes bits 16..19 from byte 7
// and 12..15 from byte 8; the serial bits 28..31 from byte 3. wacom_intuos_general(): every
// packet type reports X, Y and distance; type 5 is the rotation of an Art Pen (ABS_Z), the
// pressure, tilt and buttons of the previous general packet stay.
TEST(Intuos4Decoder, ArtPenRotationPacketsMoveThePen) {
  Intuos4Decoder dec(info(), tools());
  PenSample s;
  // Enter: Art Pen 0x10804, serial 0xF2345678.
  const uint8_t enter[10] = {0x02, 0xC2, 0x80, 0x4F, 0x23, 0x45, 0x67, 0x81, 0x00, 0x00};
  ASSERT_EQ(dec.decode(enter, 10, 1, s).status, DecodeStatus::kNoSample);
  const uint8_t pen[10] = {0x02, 0xE3, 0x12, 0x34, 0x05, 0x67, 0x7F, 0xF2, 0x14, 0x16};
  ASSERT_EQ(dec.decode(pen, 10, 2, s).status, DecodeStatus::kSample);
  EXPECT_EQ(s.tool_id, 0x100804u) << "0x10804 in the kernel's mangled form";
  EXPECT_EQ(s.tool_serial, 0xF2345678u);
  // Rotation packet (type 5): X 0x4000, Y 0x2000, distance 3, rotation raw 405 with the 0x20
  // bit set: (405 - 1) / 2 + 450 = 652.
  const uint8_t rotation[10] = {0x02, 0xEA, 0x20, 0x00, 0x10, 0x00, 0x32, 0xA0, 0x00, 0x0C};
  ASSERT_EQ(dec.decode(rotation, 10, 3, s).status, DecodeStatus::kSample);
  EXPECT_EQ(s.x_raw, 0x4000);
  EXPECT_EQ(s.y_raw, 0x2000);
  EXPECT_EQ(s.distance_raw, 3);
  EXPECT_EQ(dec.rotation(), 652);
  EXPECT_EQ(s.pressure_raw, 0x3FF) << "pressure stays from the general packet";
  EXPECT_EQ(s.tilt_x_raw, 36);
  EXPECT_EQ(s.buttons, kPenTip | kPenStylus1);
  EXPECT_EQ(s.tool, PenTool::kPen);
  EXPECT_EQ(s.tool_id, 0x100804u);
  EXPECT_DOUBLE_EQ(s.x_mm, 0x4000 / 200.0);
  // Without the 0x20 bit: 450 - 404 / 2 = 248; past 900: (2045 - 1) / 2 - 1350 = -328.
  const uint8_t rot_b[10] = {0x02, 0xEA, 0x20, 0x00, 0x10, 0x00, 0x32, 0x80, 0x00, 0x0C};
  dec.decode(rot_b, 10, 4, s);
  EXPECT_EQ(dec.rotation(), 248);
  const uint8_t rot_c[10] = {0x02, 0xEA, 0x20, 0x00, 0x10, 0x00, 0xFF, 0xA0, 0x00, 0x0C};
  dec.decode(rot_c, 10, 5, s);
  EXPECT_EQ(dec.rotation(), -328);
  // Leaving proximity ends the stroke where the rotation packet put the pen.
  const uint8_t exit[10] = {0x02, 0x80};
  ASSERT_EQ(dec.decode(exit, 10, 6, s).status, DecodeStatus::kSample);
  EXPECT_FALSE(s.in_proximity);
  EXPECT_EQ(s.x_raw, 0x4000);
  EXPECT_EQ(s.y_raw, 0x2000);
}

// wacom_intuos_general(), case 0x0a "airbrush second packet": ABS_WHEEL and the tilts, with X,
// Y and distance; pressure stays. Tool id bits 12..15 (byte 8) make 0x1480a, an eraser.
TEST(Intuos4Decoder, AirbrushSecondPacketAndHighToolBits) {
  Intuos4Decoder dec(info(), tools());
  PenSample s;
  // Airbrush 0x10902, serial 1.
  const uint8_t airbrush[10] = {0x02, 0xC2, 0x90, 0x20, 0x00, 0x00, 0x00, 0x11, 0x00, 0x00};
  dec.decode(airbrush, 10, 1, s);
  const uint8_t pen[10] = {0x02, 0xE3, 0x12, 0x34, 0x05, 0x67, 0x7F, 0xF2, 0x14, 0x16};
  ASSERT_EQ(dec.decode(pen, 10, 2, s).status, DecodeStatus::kSample);
  EXPECT_EQ(s.tool_id, 0x100902u);
  EXPECT_EQ(s.tool_serial, 1u);
  // Type 10: wheel (0xAB << 2) | 3 = 687, tilt X ((0xC5 << 1) & 0x7E | 1) - 64 = -53,
  // tilt Y 0x10 - 64 = -48, X 0x4000, Y 0x2000, distance 3.
  const uint8_t second[10] = {0x02, 0xF4, 0x20, 0x00, 0x10, 0x00, 0xAB, 0xC5, 0x90, 0x0C};
  ASSERT_EQ(dec.decode(second, 10, 3, s).status, DecodeStatus::kSample);
  EXPECT_EQ(dec.wheel(), 687);
  EXPECT_EQ(s.tilt_x_raw, -53);
  EXPECT_EQ(s.tilt_y_raw, -48);
  EXPECT_EQ(s.x_raw, 0x4000);
  EXPECT_EQ(s.distance_raw, 3);
  EXPECT_EQ(s.pressure_raw, 0x3FF);
  // A Classic Pen eraser, 0x1480a: byte 8 carries bits 12..15 (0x4), byte 7 bit 16.
  const uint8_t exit[10] = {0x02, 0x80};
  dec.decode(exit, 10, 4, s);
  const uint8_t eraser[10] = {0x02, 0xC2, 0x80, 0xA0, 0x00, 0x00, 0x00, 0x21, 0x40, 0x00};
  dec.decode(eraser, 10, 5, s);
  ASSERT_EQ(dec.decode(pen, 10, 6, s).status, DecodeStatus::kSample);
  EXPECT_EQ(s.tool, PenTool::kEraser);
  EXPECT_EQ(s.tool_id, 0x14080Au);
  EXPECT_EQ(s.tool_serial, 2u);
}

// wacom_intuos_get_tool_type(): 0x806 is the Intuos4 mouse (BTN_TOOL_MOUSE), not a pen.
TEST(Intuos4Decoder, MouseToolsGiveNoPenSamples) {
  Intuos4Decoder dec(info(), tools());
  PenSample s;
  const uint8_t mouse[10] = {0x02, 0xC2, 0x80, 0x60, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00};
  dec.decode(mouse, 10, 1, s);
  const uint8_t packet[10] = {0x02, 0xEC, 0x12, 0x34, 0x05, 0x67, 0x01, 0x00, 0x40, 0x00};
  DecodeResult r = dec.decode(packet, 10, 2, s);
  EXPECT_EQ(r.status, DecodeStatus::kNoSample);
  EXPECT_NE(r.reason.find("mouse or lens cursor"), std::string::npos) << r.reason;
}

TEST(Intuos4Decoder, RoundTripsThePenScript) {
  const PenDeviceInfo d = info();
  Intuos4Decoder dec(d, tools());
  PenSample previous{};
  bool was_in = false;
  int samples = 0;
  for (const hil::PenStep& st : hil::penScript(d.x_max, d.y_max, d.pressure_max, d.distance_max)) {
    PenSample expected, got;
    const bool expect = hil::expectedSample(st, d, true, previous, expected);
    if (st.sense && !was_in) {
      const auto enter = hil::encodeIntuos4Enter(st.tool_type, st.serial);
      ASSERT_EQ(dec.decode(enter.data(), enter.size(), 0, got).status, DecodeStatus::kNoSample);
    }
    was_in = st.sense;
    const auto pkt = st.sense ? hil::encodeIntuos4Pen(st) : hil::encodeIntuos4Exit();
    DecodeResult r = dec.decode(pkt.data(), pkt.size(), 0, got);
    ASSERT_EQ(r.status, expect ? DecodeStatus::kSample : DecodeStatus::kNoSample) << r.reason;
    if (expect) {
      EXPECT_TRUE(samePenState(got, expected)) << "sample " << samples;
      ++samples;
    }
  }
  EXPECT_EQ(samples, 32);
}

TEST(Intuos4Decoder, EraserToolAndInRangeLeaving) {
  Intuos4Decoder dec(info(), tools());
  PenSample s;
  const auto enter = hil::encodeIntuos4Enter(0x80A, 42);  // general pen, eraser end
  dec.decode(enter.data(), enter.size(), 0, s);
  hil::PenStep st;
  st.pressure = 500;
  st.x = 100;
  const auto pkt = hil::encodeIntuos4Pen(st);
  ASSERT_EQ(dec.decode(pkt.data(), pkt.size(), 1, s).status, DecodeStatus::kSample);
  EXPECT_EQ(s.tool, PenTool::kEraser);
  EXPECT_TRUE(s.tipDown());
  const uint8_t leaving[10] = {0x02, 0x20};
  ASSERT_EQ(dec.decode(leaving, 10, 2, s).status, DecodeStatus::kSample);
  EXPECT_TRUE(s.in_proximity);
  EXPECT_FALSE(s.tipDown());
  EXPECT_EQ(s.pressure_raw, 0);
  EXPECT_EQ(s.distance_raw, 63);
}

TEST(Intuos4Decoder, RejectsWrongLengthsAndOtherReports) {
  Intuos4Decoder dec(info(), tools());
  PenSample s;
  const uint8_t pkt[12] = {0x02, 0xE0};
  DecodeResult r = dec.decode(pkt, 9, 0, s);
  EXPECT_EQ(r.status, DecodeStatus::kRejected);
  EXPECT_NE(r.reason.find("short Intuos4 packet: 9 bytes"), std::string::npos) << r.reason;
  r = dec.decode(pkt, 12, 0, s);
  EXPECT_EQ(r.status, DecodeStatus::kRejected);
  EXPECT_NE(r.reason.find("oversized"), std::string::npos);
  const uint8_t pad[10] = {0x0C};
  EXPECT_EQ(dec.decode(pad, 10, 0, s).status, DecodeStatus::kOtherReport);
  EXPECT_EQ(dec.decode(pad, 0, 0, s).status, DecodeStatus::kRejected);
}

}  // namespace
}  // namespace cb::hid
