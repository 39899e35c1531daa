// Pens with only a tip (no pressure axis, no barrel buttons) through every path: the HID
// backends' decoder (the real eGalax, Nexio and IRTOUCH descriptors with the reports hid-tools
// built for them), the evdev state machine (a node with BTN_TOUCH and no ABS_PRESSURE), and
// the painter's pressure level for them (drivers/core/tip_only_pressure.h).
#include <gtest/gtest.h>

#include <linux/input.h>

#include "drivers/core/tip_only_pressure.h"
#include "drivers/evdev/evdev_pen_state.h"
#include "drivers/hid/hidapi_pen_source.h"
#include "tests/hil/tablet/pen_corpus.h"
#include "tests/unit/drivers/fixtures.h"

namespace cb {
namespace {

TEST(TipOnlyPen, HidBackendsDecodeTheRealTipOnlyPens) {
  std::string error;
  const auto devices =
      hil::readPenCorpus(std::string(CB_HID_FIXTURE_DIR) + "/pen_corpus_reports.txt", &error);
  ASSERT_TRUE(error.empty()) << error;
  int tip_only = 0;
  for (const hil::CorpusDevice& dev : devices) {
    if (dev.ranges.count("tippressure")) continue;
    SCOPED_TRACE(dev.file);
    ++tip_only;
    hid::HidPenDevice d;
    std::unique_ptr<hid::PenDecoder> decoder;
    // What the hidraw and libusb backends do with the device: its descriptor and device files.
    ASSERT_TRUE(hid::makePenDecoder(&test::shippedDevices(), dev.vendor, dev.product, dev.file,
                                    test::readFixture(dev.file), d, decoder))
        << d.error;
    EXPECT_EQ(d.protocol, "generic");
    EXPECT_FALSE(penHasPressure(d.info));
    bool touched = false;
    for (const hil::CorpusStep& st : dev.steps) {
      PenSample s;
      const hid::DecodeResult r =
          hid::decodeReport(*decoder, st.report.data(), st.report.size(), 1, s);
      ASSERT_NE(r.status, hid::DecodeStatus::kRejected) << r.reason;
      if (r.status != hid::DecodeStatus::kSample) s = PenSample{};
      EXPECT_EQ(hil::corpusMismatch(st, s), "") << st.name;
      EXPECT_EQ(s.pressure, 0.0f);
      if (s.tipDown()) {
        touched = true;
        PenSample painted = s;
        ASSERT_TRUE(applyTipOnlyPressure(painted, d.info, 0.6f));
        EXPECT_FLOAT_EQ(painted.pressure, 0.6f);
        EXPECT_EQ(painted.pressure_raw, 0);  // the device's own value stays
      }
    }
    EXPECT_TRUE(touched) << "the script touches down";
  }
  EXPECT_GE(tip_only, 4) << "eGalax x2, Nexio x2, IRTOUCH";
}

input_event ev(uint16_t type, uint16_t code, int32_t value) {
  input_event e{};
  e.type = type;
  e.code = code;
  e.value = value;
  return e;
}

TEST(TipOnlyPen, EvdevNodeWithoutPressurePaintsAtTheLevel) {
  PenDeviceInfo info;  // an eGalax pen node: X/Y, BTN_TOUCH, no ABS_PRESSURE
  info.x_max = 2047;
  info.y_max = 2047;
  info.x_res = info.y_res = 10;
  EvdevPenState state(info);
  PenSample s;
  state.feed(ev(EV_KEY, BTN_TOOL_PEN, 1), s);
  state.feed(ev(EV_ABS, ABS_X, 500), s);
  state.feed(ev(EV_ABS, ABS_Y, 600), s);
  ASSERT_TRUE(state.feed(ev(EV_SYN, SYN_REPORT, 0), s));
  EXPECT_TRUE(s.in_proximity);
  EXPECT_FALSE(applyTipOnlyPressure(s, info, 0.6f)) << "hovering: no pressure";
  state.feed(ev(EV_KEY, BTN_TOUCH, 1), s);
  ASSERT_TRUE(state.feed(ev(EV_SYN, SYN_REPORT, 0), s));
  ASSERT_TRUE(s.tipDown());
  EXPECT_EQ(s.pressure, 0.0f);
  PenSample strong = s;
  ASSERT_TRUE(applyTipOnlyPressure(strong, info, 2.0f));
  EXPECT_FLOAT_EQ(strong.pressure, 1.0f) << "clamped";
  // A sample that carries a pressure although the device says it has none (a journal without
  // its device record) keeps it.
  PenSample carried = s;
  carried.pressure_raw = 300;
  carried.pressure = 0.3f;
  EXPECT_FALSE(applyTipOnlyPressure(carried, info, 0.6f));
  EXPECT_FLOAT_EQ(carried.pressure, 0.3f);
  // A pen with pressure is never overridden.
  PenDeviceInfo with = info;
  with.pressure_max = 2047;
  PenSample p = s;
  p.pressure = 0.25f;
  EXPECT_FALSE(applyTipOnlyPressure(p, with, 0.6f));
  EXPECT_FLOAT_EQ(p.pressure, 0.25f);
}

}  // namespace
}  // namespace cb
