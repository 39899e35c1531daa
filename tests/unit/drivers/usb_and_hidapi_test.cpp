// Host-side checks of the USB/hidapi plumbing that need no tablet (the tablet itself is proven
// in tests/hil/tablet).
#include <gtest/gtest.h>

#include "drivers/evdev/evdev_pen_source.h"
#include "drivers/hid/hidapi_library.h"
#include "drivers/open_pen_source.h"
#include "drivers/usb/usb_devices.h"

namespace cb {
namespace {

TEST(UsbPath, ParsesHidapiLibusbPaths) {
  usb::UsbInterfaceLocation l;
  ASSERT_TRUE(usb::parseHidapiLibusbPath("1-1:1.0", l));
  EXPECT_EQ(l.bus, 1);
  EXPECT_EQ(l.ports, std::vector<uint8_t>({1}));
  EXPECT_EQ(l.interface, 0);
  ASSERT_TRUE(usb::parseHidapiLibusbPath("3-2.4.1:1.2", l));
  EXPECT_EQ(l.bus, 3);
  EXPECT_EQ(l.ports, std::vector<uint8_t>({2, 4, 1}));
  EXPECT_EQ(l.interface, 2);
  for (const char* bad : {"", "1-", "1-1", "x-1:1.0", "1-1:1", "1-1.:1.0", "1-999:1.0",
                          "/dev/hidraw0", "1-1:1.0/../../x"})
    EXPECT_FALSE(usb::parseHidapiLibusbPath(bad, l)) << bad;
}

TEST(Hidapi, BothBackendsLoadSideBySide) {
  // libhidapi-hidraw and libhidapi-libusb export the same symbols; dlopen keeps them apart.
  std::string error;
  auto hidraw = hid::loadHidapi(hid::HidapiBackend::kHidraw, &error);
  ASSERT_TRUE(hidraw) << error;
  auto libusb = hid::loadHidapi(hid::HidapiBackend::kLibusb, &error);
  ASSERT_TRUE(libusb) << error;
  EXPECT_NE(hidraw->enumerate, libusb->enumerate);
  // Enumerating works (lists nothing on a machine without HID devices).
  hid_device_info* a = hidraw->enumerate(0x056A, 0);
  hidraw->free_enumeration(a);
  hid_device_info* b = libusb->enumerate(0x056A, 0);
  libusb->free_enumeration(b);
}

TEST(OpenPenSource, MissingDeviceIsAStateNotAnExit) {
  EvdevPenSourceOptions o;
  o.input_dir = "/nonexistent-input-dir";
  EvdevPenSource src(o);
  EXPECT_EQ(src.connection(), PenConnection::kSearching);
  std::vector<PenSample> got;
  src.poll(10, got);
  EXPECT_TRUE(got.empty());
  EXPECT_NE(src.statusMessage().find("no pen found"), std::string::npos) << src.statusMessage();
}

TEST(OpenPenSource, UnknownBackendAndReplayWithoutFileAreNamed) {
  std::string error;
  PenSourceOptions o;
  o.backend = "bluetooth";
  EXPECT_FALSE(openPenSource(o, &error));
  EXPECT_NE(error.find("unknown pen backend 'bluetooth'"), std::string::npos);
  o.backend = "replay";
  EXPECT_FALSE(openPenSource(o, &error));
  EXPECT_NE(error.find("journal file"), std::string::npos);
}

}  // namespace
}  // namespace cb
