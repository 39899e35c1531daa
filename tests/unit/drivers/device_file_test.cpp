// The device files (config/devices, drivers/devices/device_file.h): what the shipped files say,
// the loader's FILE:LINE:COL errors, report-descriptor fix-ups, and a tablet added as data only
// (the Intuos5 touch M, which before the device files needed a code change).
#include "drivers/devices/device_file.h"

#include <gtest/gtest.h>

#include <cmath>

#include "drivers/core/pen_units.h"
#include "drivers/hid/hidapi_pen_source.h"
#include "tests/hil/tablet/intuos4_handbuilt.h"
#include "tests/hil/tablet/pen_script.h"
#include "tests/unit/drivers/fixtures.h"

namespace cb {
namespace {

DeviceFileLoad parseOne(const std::string& text) {
  return parseDeviceFiles({{"t.toml", text}});
}

const char* kMinimal = R"(
[family]
name = "Test"
vendor = 0x1234
driver = "hid-generic"
protocol = "descriptor"
)";

TEST(DeviceFiles, ShippedFilesLoadCleanly) {
  const DeviceFileLoad load = loadDeviceDirectory(std::string(CB_SOURCE_DIR) + "/config/devices");
  EXPECT_TRUE(load.errors.empty()) << load.errors.front();
  EXPECT_EQ(load.database->files().size(), 14u);
  // hid-uclogic's v2 pens: hid-input's rules on the driver's descriptor, and its 100 ms
  // in-range timer (uclogic_inrange_timeout) as the idle timeout.
  const DeviceEntry* huion = load.database->find(0x256C, 0x006E);
  ASSERT_NE(huion, nullptr);
  EXPECT_EQ(huion->rules, PenDriverRules::kHidInput);
  EXPECT_EQ(huion->idle_proximity_timeout_ms, 100);
  // Intuos4: the model table that was compiled into the decoder, now data.
  const DeviceEntry* i4 = load.database->find(0x056A, 0x00BB);
  ASSERT_NE(i4, nullptr);
  EXPECT_EQ(i4->name, "Wacom Intuos4 12x19");
  EXPECT_EQ(i4->protocol, PenProtocol::kIntuos4);
  EXPECT_EQ(i4->rules, PenDriverRules::kWacom);
  EXPECT_EQ(i4->info.x_max, 97536);
  EXPECT_EQ(i4->info.y_max, 60960);
  EXPECT_EQ(i4->info.pressure_max, 2047);
  EXPECT_DOUBLE_EQ(i4->info.x_res, 200.0);
  EXPECT_NEAR(i4->info.tilt_res, 57 * M_PI / 180.0, 1e-12);
  EXPECT_EQ(i4->mode_report_id, 2);
  EXPECT_EQ(i4->mode_value, 2);
  EXPECT_EQ(i4->fuzz.position, 4);
  EXPECT_EQ(i4->fuzz.tilt, 1);
  EXPECT_EQ(i4->fuzz.distance, 1);
  EXPECT_EQ(i4->fuzz.pressure, 0);
  EXPECT_EQ(i4->idle_proximity_timeout_ms, 100);
  ASSERT_TRUE(i4->tools);
  EXPECT_TRUE(i4->tools->isEraser(0x80A));
  EXPECT_TRUE(i4->tools->isEraser(0x1480A));
  EXPECT_TRUE(i4->tools->isPuck(0x806));  // Intuos4 mouse
  EXPECT_TRUE(i4->tools->isPuck(0x006));  // Intuos4 lens cursor
  EXPECT_FALSE(i4->tools->isEraser(0x802));
  // Another Wacom falls to the vendor-wide descriptor family, with the generic path's fuzz.
  const DeviceEntry* pth = load.database->find(0x056A, 0x0357);
  ASSERT_NE(pth, nullptr);
  EXPECT_EQ(pth->protocol, PenProtocol::kDescriptor);
  EXPECT_FALSE(pth->product.has_value());
  EXPECT_EQ(pth->fuzz.position, 4);
  EXPECT_EQ(pth->fuzz.tilt, 0);
  // A vendor without a file has no entry: hid-input's rules.
  EXPECT_EQ(load.database->find(0x1234, 0x5678), nullptr);
  // The corpus's other pens are listed (for the udev rules) with hid-input's rules, no quirks.
  const DeviceEntry* xppen = load.database->find(0x28BD, 0x093A);
  ASSERT_NE(xppen, nullptr);
  EXPECT_EQ(xppen->rules, PenDriverRules::kHidInput);
  EXPECT_EQ(xppen->protocol, PenProtocol::kDescriptor);
  EXPECT_FALSE(xppen->fuzz.any());
  EXPECT_TRUE(xppen->fixups.empty());
  EXPECT_EQ(load.database->find(0x28BD, 0x0001), nullptr) << "only the models listed";
}

// Each mistake names file, line and column, and what is wrong; the file adds nothing.
TEST(DeviceFiles, MistakesAreReportedWithFileLineColumn) {
  struct Case {
    std::string text, expect;
  };
  const std::vector<Case> cases = {
      {std::string(kMinimal) + "fuzzz = 3\n", "t.toml:7:1: family.fuzzz: unknown key"},
      {std::string(kMinimal) + "[family.fuzz]\nposition = -1\n",
       "t.toml:8:12: family.fuzz.position: -1 is outside 0..65536"},
      {"[family]\nname = \"x\"\nvendor = 70000\ndriver = \"wacom\"\nprotocol = \"descriptor\"\n",
       "t.toml:3:10: family.vendor: 70000 is outside 0..65535"},
      {"[family]\nname = \"x\"\nvendor = 1\ndriver = \"evdev\"\nprotocol = \"descriptor\"\n",
       "t.toml:4:10: family.driver: \"evdev\": expected \"wacom\" or \"hid-generic\""},
      {"[family]\nname = \"x\"\nvendor = 1\ndriver = \"wacom\"\n",
       "t.toml:1:1: family.protocol: missing"},
      {std::string(kMinimal) + "tool_table = \"nope\"\n",
       "t.toml:7:14: family.tool_table: no [tool_table.nope] in any device file"},
      {std::string(kMinimal) + "[[model]]\nproduct = 1\nname = \"a\"\n[[model]]\nproduct = 1\n"
                               "name = \"b\"\n",
       "t.toml:11:11: model.product: listed twice"},
      {std::string(kMinimal) + "[[report_fixup]]\noffset = 3\nexpect = [1, 2]\nreplace = [3]\n",
       "t.toml:10:11: report_fixup.replace: must have as many bytes as expect (2)"},
      {"[family\nname = 1\n", "t.toml:1:8: "},  // a TOML syntax error
      // A mistake in the file's tool table keeps its family out too (a fuzzer's find).
      {std::string(kMinimal) + "[tool_table.t]\neraser = [1]\ny_max = 2\n",
       "t.toml:9:1: tool_table.t.y_max: unknown key"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    const DeviceFileLoad load = parseOne(cases[i].text);
    ASSERT_FALSE(load.errors.empty()) << "case " << i;
    EXPECT_EQ(load.errors.front().rfind(cases[i].expect, 0), 0u)
        << "case " << i << ": " << load.errors.front();
    EXPECT_TRUE(load.database->entries().empty()) << "case " << i;
  }
  // Protocol intuos4 without models says what it needs.
  const DeviceFileLoad noModels = parseOne(
      "[family]\nname = \"x\"\nvendor = 1\ndriver = \"wacom\"\nprotocol = \"intuos4\"\n"
      "[family.ranges]\nresolution_per_mm = 200\npressure_max = 2047\ntilt_min = -64\n"
      "tilt_max = 63\ntilt_per_radian = 57\ndistance_max = 63\n");
  ASSERT_EQ(noModels.errors.size(), 1u);
  EXPECT_NE(noModels.errors[0].find("model: protocol \"intuos4\" needs at least one [[model]]"),
            std::string::npos)
      << noModels.errors[0];
  // A sound file loads; a USB id in two files is refused at the second, naming the first.
  const DeviceFileLoad two = parseDeviceFiles({{"a.toml", kMinimal}, {"b.toml", kMinimal}});
  ASSERT_EQ(two.errors.size(), 1u);
  EXPECT_EQ(two.errors[0], "b.toml:2:1: model: this USB id already has an entry at a.toml:2:1");
  EXPECT_EQ(two.database->entries().size(), 1u);
}

TEST(DeviceFiles, MissingFolderIsAnError) {
  const DeviceFileLoad load = loadDeviceDirectory("/nonexistent/cloudbrush-devices");
  ASSERT_EQ(load.errors.size(), 1u);
  EXPECT_NE(load.errors[0].find("/nonexistent/cloudbrush-devices: cannot list"), std::string::npos);
  EXPECT_TRUE(load.database->entries().empty());
}

// A fix-up changes the descriptor only where its expected bytes are, so the device's original
// (libusb) and the kernel's rewrite (hidraw) end up the same; a second application is a no-op.
TEST(DeviceFiles, ReportFixupAppliesOnlyWhereTheOriginalBytesAre) {
  const DeviceFileLoad load = parseOne(std::string(kMinimal) +
                                       "[[report_fixup]]\nsize = 6\noffset = 2\n"
                                       "expect = [0x09, 0x3c]\nreplace = [0x09, 0x45]\n");
  ASSERT_TRUE(load.errors.empty()) << load.errors.front();
  const DeviceEntry* e = load.database->find(0x1234, 0x0001);
  ASSERT_NE(e, nullptr);
  ASSERT_EQ(e->fixups.size(), 1u);
  EXPECT_EQ(e->fixups[0].where, "t.toml:7:1");
  std::vector<uint8_t> original = {0x05, 0x0D, 0x09, 0x3C, 0x15, 0x00};
  EXPECT_EQ(applyReportFixups(e->fixups, original), 1);
  EXPECT_EQ(original, (std::vector<uint8_t>{0x05, 0x0D, 0x09, 0x45, 0x15, 0x00}));
  EXPECT_EQ(applyReportFixups(e->fixups, original), 0);  // already fixed (what hidraw shows)
  std::vector<uint8_t> longer = {0x05, 0x0D, 0x09, 0x3C, 0x15, 0x00, 0xC0};
  EXPECT_EQ(applyReportFixups(e->fixups, longer), 0);  // another size: not this descriptor
}

// Adding a tablet is a data change: the Intuos5 touch M (PTH-650, 056a:0027) speaks the Intuos4
// protocol; config/devices/wacom-intuos5.toml alone makes the HID backends decode it with the
// kernel's ranges (wacom_features_0x27), its mode switch and the Wacom tool table.
TEST(DeviceFiles, Intuos5AddedAsDataDecodesThePenScript) {
  hid::HidPenDevice device;
  std::unique_ptr<hid::PenDecoder> decoder;
  ASSERT_TRUE(hid::makePenDecoder(&test::shippedDevices(), 0x056A, 0x0027, "Wacom Co.,Ltd. PTH-650",
                                  hil::handBuiltIntuos4Descriptor(), device, decoder))
      << device.error;
  EXPECT_EQ(device.protocol, "intuos4");
  EXPECT_EQ(device.mode_report_id, 2);
  const PenDeviceInfo& d = device.info;
  EXPECT_STREQ(d.name, "Wacom Intuos5 touch M");
  EXPECT_EQ(d.x_max, 44704);
  EXPECT_EQ(d.y_max, 27940);
  EXPECT_NEAR(d.x_max / d.x_res, 223.52, 1e-9);  // mm
  // Without the file the same device is not an Intuos4-protocol tablet: the hand-built
  // descriptor names no pen fields, so nothing decodes it.
  DeviceDatabase empty;
  hid::HidPenDevice bare;
  std::unique_ptr<hid::PenDecoder> none;
  EXPECT_FALSE(hid::makePenDecoder(&empty, 0x056A, 0x0027, "x", hil::handBuiltIntuos4Descriptor(),
                                   bare, none));

  PenSample previous{};
  bool was_in = false;
  int samples = 0;
  for (const hil::PenStep& st : hil::penScript(d.x_max, d.y_max, d.pressure_max, d.distance_max)) {
    PenSample expected, got;
    const bool expect = hil::expectedSample(st, d, true, previous, expected);
    if (st.sense && !was_in) {
      const auto enter = hil::encodeIntuos4Enter(st.tool_type, st.serial);
      hid::decodeReport(*decoder, enter.data(), enter.size(), 0, got);
    }
    was_in = st.sense;
    const auto pkt = st.sense ? hil::encodeIntuos4Pen(st) : hil::encodeIntuos4Exit();
    const hid::DecodeResult r = hid::decodeReport(*decoder, pkt.data(), pkt.size(), 0, got);
    ASSERT_EQ(r.status, expect ? hid::DecodeStatus::kSample : hid::DecodeStatus::kNoSample);
    if (expect) {
      EXPECT_TRUE(samePenState(got, expected)) << "sample " << samples;
      ++samples;
    }
  }
  EXPECT_EQ(samples, 32);
}

}  // namespace
}  // namespace cb
