#include "drivers/hid/hid_pen_decoder.h"

#include <gtest/gtest.h>

#include <cmath>

#include "drivers/core/pen_units.h"
#include "tests/hil/tablet/pen_script.h"
#include "tests/unit/drivers/fixtures.h"

namespace cb::hid {
namespace {

class HidPenDecoderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto bytes = test::readFixture("wacom-pth660_v145.rdesc");
    ParseResult r = parseReportDescriptor(bytes.data(), bytes.size());
    ASSERT_TRUE(r.descriptor);
    layout_ = *findPenLayout(*r.descriptor).layout;
    info_ = penDeviceInfo(layout_, 0x056A, 0x0357, "PTH-660");
  }
  PenLayout layout_;
  PenDeviceInfo info_;
};

TEST_F(HidPenDecoderTest, DecodesTheWholePenScript) {
  HidPenDecoder decoder(layout_, info_, PenDriverRules::kWacom,
                        test::shippedEntry(0x056A, 0x0357).tools);
  PenSample previous{};
  int samples = 0;
  for (const hil::PenStep& step :
       hil::penScript(info_.x_max, info_.y_max, info_.pressure_max, info_.distance_max)) {
    const std::vector<uint8_t> report = hil::encodePenReport(layout_, step);
    PenSample expected, got;
    const bool expect = hil::expectedSample(step, info_, false, previous, expected);
    DecodeResult r = decoder.decode(report.data(), report.size(), 1000 + samples, got);
    ASSERT_EQ(r.status, expect ? DecodeStatus::kSample : DecodeStatus::kNoSample) << r.reason;
    if (expect) {
      EXPECT_TRUE(samePenState(got, expected)) << "step " << samples;
      ++samples;
    }
  }
  EXPECT_EQ(samples, 32);
}

TEST_F(HidPenDecoderTest, UnitConversion) {
  HidPenDecoder decoder(layout_, info_, PenDriverRules::kWacom,
                        test::shippedEntry(0x056A, 0x0357).tools);
  hil::PenStep s;
  s.x = 44800;  // the far edge: 224 mm at 200 units/mm
  s.y = 200;
  s.pressure = 8191;
  s.tilt_x = 63;
  s.tilt_y = -64;
  s.distance = 63;
  s.tip = true;
  s.serial = 7;
  s.tool_type = 0x802;
  const auto report = hil::encodePenReport(layout_, s);
  PenSample got;
  ASSERT_EQ(decoder.decode(report.data(), report.size(), 5, got).status, DecodeStatus::kSample);
  EXPECT_DOUBLE_EQ(got.x_mm, 224.0);
  EXPECT_DOUBLE_EQ(got.y_mm, 1.0);
  EXPECT_FLOAT_EQ(got.pressure, 1.0f);
  EXPECT_NEAR(got.tilt_x_deg, 63 / (57 * M_PI / 180.0), 1e-4);  // 63.3 degrees
  EXPECT_NEAR(got.tilt_y_deg, -64.33, 0.01);
  EXPECT_FLOAT_EQ(got.distance, 1.0f);
  EXPECT_TRUE(got.tipDown());
  EXPECT_EQ(got.tool, PenTool::kPen);
  EXPECT_EQ(got.tool_id, 0x802u);
  EXPECT_EQ(got.t_ns, 5);
}

// The kernel's HID core (hid-core.c, hid_report_raw_event): a short report is refused, bytes past
// the descriptor's length are not read.
TEST_F(HidPenDecoderTest, RejectsShortReportsAndIgnoresTrailingBytes) {
  HidPenDecoder decoder(layout_, info_, PenDriverRules::kWacom,
                        test::shippedEntry(0x056A, 0x0357).tools);
  hil::PenStep s;
  s.tip = true;
  s.pressure = 3000;
  s.x = 2222;
  auto report = hil::encodePenReport(layout_, s);
  PenSample out;
  DecodeResult r = decoder.decode(report.data(), report.size() - 1, 0, out);
  EXPECT_EQ(r.status, DecodeStatus::kRejected);
  EXPECT_NE(r.reason.find("short pen report: " + std::to_string(report.size() - 1) + " bytes"),
            std::string::npos)
      << r.reason;
  const size_t exact = report.size();
  report.resize(exact + 1, 0xFF);  // one byte more, all bits set
  r = decoder.decode(report.data(), report.size(), 1, out);
  ASSERT_EQ(r.status, DecodeStatus::kSample) << r.reason;
  EXPECT_EQ(out.x_raw, 2222);
  EXPECT_EQ(out.pressure_raw, 3000);
  report.resize(64, 0xFF);
  r = decoder.decode(report.data(), report.size(), 2, out);
  ASSERT_EQ(r.status, DecodeStatus::kSample) << r.reason;
  EXPECT_EQ(out.x_raw, 2222);
  report[0] = 17;  // the pad report
  r = decoder.decode(report.data(), report.size(), 3, out);
  EXPECT_EQ(r.status, DecodeStatus::kOtherReport);
  EXPECT_EQ(decoder.decode(report.data(), 0, 0, out).status, DecodeStatus::kRejected);
}

TEST_F(HidPenDecoderTest, DisconnectMidStrokeEndsTheStroke) {
  HidPenDecoder decoder(layout_, info_, PenDriverRules::kWacom,
                        test::shippedEntry(0x056A, 0x0357).tools);
  hil::PenStep s;
  s.tip = true;
  s.pressure = 4000;
  s.x = 1234;
  s.serial = 1;
  s.tool_type = 0x802;
  const auto report = hil::encodePenReport(layout_, s);
  PenSample down, out;
  ASSERT_EQ(decoder.decode(report.data(), report.size(), 1, down).status, DecodeStatus::kSample);
  ASSERT_TRUE(decoder.disconnect(2, out));
  EXPECT_FALSE(out.in_proximity);
  EXPECT_FALSE(out.tipDown());
  EXPECT_EQ(out.pressure_raw, 0);
  EXPECT_EQ(out.x_raw, 1234);
  EXPECT_EQ(out.t_ns, 2);
  EXPECT_FALSE(decoder.disconnect(3, out)) << "nothing to end twice";
}

TEST_F(HidPenDecoderTest, InvertSelectsTheEraserUntilProximityOut) {
  HidPenDecoder decoder(layout_, info_, PenDriverRules::kWacom,
                        test::shippedEntry(0x056A, 0x0357).tools);
  hil::PenStep s;
  s.invert = true;
  s.serial = 9;
  s.tool_type = 0x802;
  auto report = hil::encodePenReport(layout_, s);
  PenSample out;
  decoder.decode(report.data(), report.size(), 1, out);
  EXPECT_EQ(out.tool, PenTool::kEraser);
  s.invert = false;  // the tool chosen when entering range sticks, as in the kernel
  report = hil::encodePenReport(layout_, s);
  decoder.decode(report.data(), report.size(), 2, out);
  EXPECT_EQ(out.tool, PenTool::kEraser);
}

}  // namespace
}  // namespace cb::hid
