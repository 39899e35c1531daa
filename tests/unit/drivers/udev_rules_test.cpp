// The udev rules come from the device files: the shipped config/udev/70-cloudbrush-tablet.rules
// is exactly what `udevRules` makes of config/devices (so a device file added without the rules
// generated again fails here), every pen of the HID corpus (tests/fixtures/hid, ids in the
// file names) gets a hidraw and a USB rule whose patterns match its kernel names, and a device
// no file names gets none.
#include "drivers/devices/udev_rules.h"

#include <fnmatch.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>

#include "drivers/devices/device_file.h"
#include "tests/support/file_text.h"

namespace cb {
namespace {

using cb::test::readText;

// What a rule line's `KEY=="VALUE"` patterns would match, the way udev compares them (fnmatch
// globs; a hidraw node's KERNELS is its HID device's name, BUS:VENDOR:PRODUCT.N in hex capitals).
bool hidrawOpened(const std::string& rules, const std::string& hid_name) {
  static const std::regex line(
      R"re(SUBSYSTEM=="hidraw", KERNELS=="([^"]+)", GROUP="input", MODE="0660")re");
  std::istringstream in(rules);
  for (std::string l; std::getline(in, l);) {
    std::smatch m;
    if (std::regex_match(l, m, line) && fnmatch(m[1].str().c_str(), hid_name.c_str(), 0) == 0)
      return true;
  }
  return false;
}

bool usbOpened(const std::string& rules, const std::string& vendor, const std::string& product) {
  static const std::regex line(
      R"re(SUBSYSTEM=="usb", ENV\{DEVTYPE\}=="usb_device", ATTR\{idVendor\}=="([0-9a-f]{4})", (ATTR\{idProduct\}=="([0-9a-f]{4})", )?GROUP="input", MODE="0660")re");
  std::istringstream in(rules);
  for (std::string l; std::getline(in, l);) {
    std::smatch m;
    if (std::regex_match(l, m, line) && m[1] == vendor && (!m[2].matched || m[3] == product))
      return true;
  }
  return false;
}

std::string upper(std::string s) {
  for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

TEST(UdevRules, TheShippedRulesAreWhatTheDeviceFilesGive) {
  const DeviceFileLoad load = loadDeviceDirectory(std::string(CB_SOURCE_DIR) + "/config/devices");
  ASSERT_TRUE(load.errors.empty()) << load.errors.front();
  const std::string generated = udevRules(*load.database);
  EXPECT_EQ(readText(std::string(CB_SOURCE_DIR) + "/config/udev/70-cloudbrush-tablet.rules"),
            generated)
      << "config/udev/70-cloudbrush-tablet.rules is stale: regenerate it with "
         "`cloudbrush devices --udev-rules > config/udev/70-cloudbrush-tablet.rules`";
}

TEST(UdevRules, EveryPenOfTheCorpusIsOpenedAndNothingElse) {
  const DeviceFileLoad load = loadDeviceDirectory(std::string(CB_SOURCE_DIR) + "/config/devices");
  const std::string rules = udevRules(*load.database);
  // Non-Wacom corpus files carry their USB id in their name: NAME_VVVV_PPPP.rdesc.
  static const std::regex id(R"(.*_([0-9a-f]{4})_([0-9a-f]{4})\.rdesc)");
  int checked = 0;
  for (const auto& f : std::filesystem::directory_iterator(CB_HID_FIXTURE_DIR)) {
    std::smatch m;
    const std::string name = f.path().filename().string();
    if (!std::regex_match(name, m, id)) continue;
    const std::string v = m[1], p = m[2];
    for (const char* bus : {"0003", "0018", "0005"})
      EXPECT_TRUE(hidrawOpened(rules, std::string(bus) + ":" + upper(v) + ":" + upper(p) + ".0007"))
          << name << " on bus " << bus;
    EXPECT_TRUE(usbOpened(rules, v, p)) << name;
    ++checked;
  }
  EXPECT_GE(checked, 15);
  // Wacom: every product (wacom-generic.toml is vendor-wide), on USB and Bluetooth.
  EXPECT_TRUE(hidrawOpened(rules, "0003:056A:00B9.0001"));
  EXPECT_TRUE(hidrawOpened(rules, "0005:056A:0357.0003"));
  EXPECT_TRUE(usbOpened(rules, "056a", "00b9"));
  // A device no file names, or another product of a listed vendor: no rule.
  EXPECT_FALSE(hidrawOpened(rules, "0003:1234:5678.0001"));
  EXPECT_FALSE(usbOpened(rules, "1234", "5678"));
  EXPECT_FALSE(hidrawOpened(rules, "0003:256C:0001.0001"));
  EXPECT_FALSE(usbOpened(rules, "256c", "0001"));
  EXPECT_FALSE(hidrawOpened(rules, "0003:0001:256C.0001")) << "the vendor field only";
}

TEST(UdevRules, ANewDeviceFileGivesItsRules) {
  const DeviceFileLoad load = parseDeviceFiles({{"acme.toml", R"(
[family]
name = "Acme pads"
vendor = 0x1234
driver = "hid-generic"
protocol = "descriptor"

[[model]]
product = 0x5678
name = "Acme Pad 1"
)"}});
  ASSERT_TRUE(load.errors.empty()) << load.errors.front();
  const std::string rules = udevRules(*load.database);
  EXPECT_TRUE(hidrawOpened(rules, "0003:1234:5678.0001"));
  EXPECT_TRUE(usbOpened(rules, "1234", "5678"));
  EXPECT_FALSE(hidrawOpened(rules, "0003:1234:5679.0001"));
  EXPECT_NE(rules.find("# acme.toml: Acme pads"), std::string::npos);
}

}  // namespace
}  // namespace cb
