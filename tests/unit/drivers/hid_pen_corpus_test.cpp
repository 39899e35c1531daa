// The pen-device corpus (tests/fixtures/hid): every real descriptor parses, and for every
// non-Wacom pen a scripted motion (hover, touch, pressure ramp, tilt sweep, buttons, eraser, out
// of range) decodes field by field. The reports and their expected values come from
// pen_corpus_reports.txt, written by hid-tools' own parser and encoder
// (make_pen_corpus_reports.py), not by the code under test.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "drivers/hid/hid_pen_decoder.h"
#include "drivers/hid/hid_pen_layout.h"
#include "drivers/hid/hid_report_descriptor.h"
#include "tests/hil/tablet/pen_corpus.h"
#include "tests/unit/drivers/fixtures.h"

namespace cb::hid {
namespace {

TEST(HidPenCorpus, EveryVendoredDescriptorParses) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(CB_HID_FIXTURE_DIR)) {
    if (entry.path().extension() != ".rdesc") continue;
    const std::string name = entry.path().filename().string();
    SCOPED_TRACE(name);
    const auto bytes = test::readFixture(name);
    ParseResult r = parseReportDescriptor(bytes.data(), bytes.size());
    ASSERT_TRUE(r.descriptor) << r.error;
    PenLayoutResult l = findPenLayout(*r.descriptor);
    EXPECT_TRUE(l.layout) << l.error;
    ++count;
  }
  EXPECT_GE(count, 20);
}

TEST(HidPenCorpus, ScriptedMotionDecodesFieldByField) {
  std::string error;
  const std::vector<hil::CorpusDevice> devices =
      hil::readPenCorpus(std::string(CB_HID_FIXTURE_DIR) + "/pen_corpus_reports.txt", &error);
  ASSERT_TRUE(error.empty()) << error;
  ASSERT_GE(devices.size(), 15u) << "pen_corpus_reports.txt lists the non-Wacom pens";
  size_t checked = 0;
  for (const hil::CorpusDevice& dev : devices) {
    SCOPED_TRACE(dev.file);
    const auto bytes = test::readFixture(dev.file);
    ParseResult parsed = parseReportDescriptor(bytes.data(), bytes.size());
    ASSERT_TRUE(parsed.descriptor) << parsed.error;
    PenLayoutResult found = findPenLayout(*parsed.descriptor);
    ASSERT_TRUE(found.layout) << found.error;
    const PenLayout& l = *found.layout;
    EXPECT_EQ(l.report_id, dev.report_id);
    EXPECT_EQ(l.report_bytes, dev.report_bytes);
    const PenDeviceInfo info = penDeviceInfo(l, dev.vendor, dev.product, dev.file.c_str());
    auto range = [&](const char* k) {
      return dev.ranges.count(k) ? dev.ranges.at(k) : hil::CorpusRange{};
    };
    EXPECT_EQ(info.x_max, range("x").max);
    EXPECT_EQ(info.y_max, range("y").max);
    EXPECT_EQ(info.pressure_max, range("tippressure").max);
    EXPECT_EQ(info.tilt_min, range("xtilt").min);
    EXPECT_EQ(info.tilt_max, range("xtilt").max);
    EXPECT_EQ(l.pressure.present, dev.ranges.count("tippressure") == 1);
    EXPECT_EQ(l.eraser.present, dev.ranges.count("eraser") == 1);
    EXPECT_EQ(l.invert.present, dev.ranges.count("invert") == 1);

    HidPenDecoder decoder(l, info, test::shippedDevices().rulesFor(dev.vendor, dev.product));
    int64_t t = 0;
    for (const hil::CorpusStep& st : dev.steps) {
      SCOPED_TRACE("pen_corpus_reports.txt:" + std::to_string(st.line) + " " + st.name);
      PenSample s;
      DecodeResult r = decoder.decode(st.report.data(), st.report.size(), ++t, s);
      ASSERT_NE(r.status, DecodeStatus::kRejected) << r.reason;
      if (r.status != DecodeStatus::kSample) s = PenSample{};  // nothing in proximity
      EXPECT_EQ(hil::corpusMismatch(st, s, /*z_is_distance=*/true), "");
      ++checked;
    }
  }
  EXPECT_GE(checked, 200u);
}

// One test per pen usage hid-input maps (drivers/hid/README.md, "Pen usages"): the corpus has a
// device with it and steps that change it, and every step of those devices decodes as the
// script (hid-tools' reports) says.
class HidPenUsage : public testing::TestWithParam<const char*> {};

TEST_P(HidPenUsage, DecodesAsHidInputMapsIt) {
  const std::string usage = GetParam();
  std::string error;
  const std::vector<hil::CorpusDevice> devices =
      hil::readPenCorpus(std::string(CB_HID_FIXTURE_DIR) + "/pen_corpus_reports.txt", &error);
  ASSERT_TRUE(error.empty()) << error;
  size_t changes = 0;
  for (const hil::CorpusDevice& dev : devices) {
    if (!dev.ranges.count(usage)) continue;
    SCOPED_TRACE(dev.file);
    const auto bytes = test::readFixture(dev.file);
    ParseResult parsed = parseReportDescriptor(bytes.data(), bytes.size());
    ASSERT_TRUE(parsed.descriptor) << parsed.error;
    PenLayoutResult found = findPenLayout(*parsed.descriptor);
    ASSERT_TRUE(found.layout) << found.error;
    const PenDeviceInfo info = penDeviceInfo(*found.layout, dev.vendor, dev.product, "usage");
    HidPenDecoder decoder(*found.layout, info,
                          test::shippedDevices().rulesFor(dev.vendor, dev.product));
    int32_t previous = dev.ranges.at(usage).min;
    int64_t t = 0;
    for (const hil::CorpusStep& st : dev.steps) {
      SCOPED_TRACE("pen_corpus_reports.txt:" + std::to_string(st.line) + " " + st.name);
      PenSample s;
      DecodeResult r = decoder.decode(st.report.data(), st.report.size(), ++t, s);
      ASSERT_NE(r.status, DecodeStatus::kRejected) << r.reason;
      if (r.status != DecodeStatus::kSample) s = PenSample{};
      EXPECT_EQ(hil::corpusMismatch(st, s, /*z_is_distance=*/true), "");
      if (st.values.count(usage) && st.value(usage) != previous) ++changes;
      if (st.values.count(usage)) previous = st.value(usage);
    }
  }
  EXPECT_GE(changes, 1u) << "no corpus device changes " << usage;
}

INSTANTIATE_TEST_SUITE_P(EveryPenUsage, HidPenUsage,
                         testing::Values("tipswitch", "touch", "secondarytipswitch", "inrange",
                                         "invert", "eraser", "barrelswitch",
                                         "secondarybarrelswitch", "tabletpick", "tippressure",
                                         "xtilt", "ytilt", "z", "barrelpressure", "azimuth",
                                         "altitude", "twist", "contactid", "znotdistance"),
                         [](const testing::TestParamInfo<const char*>& i) {
                           return std::string(i.param);
                         });

}  // namespace
}  // namespace cb::hid
