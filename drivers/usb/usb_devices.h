// libusb: USB identity of tablets (VID/PID/serial/strings), the HID report descriptor read
// straight from the device, and hotplug notification.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

struct libusb_context;

namespace cb::usb {

inline constexpr uint16_t kWacomVendor = 0x056A;

struct UsbDeviceIdentity {
  uint16_t vendor = 0, product = 0;
  uint8_t bus = 0, address = 0;
  std::string manufacturer, product_name, serial;  // empty when the device cannot be opened
  bool opened = false;                             // strings were readable
  std::string open_error;                          // why not, e.g. permission denied
};

// Devices on every bus, filtered by vendor (0: all).
std::vector<UsbDeviceIdentity> listUsbDevices(uint16_t vendor = kWacomVendor);

// Where a USB interface sits: bus, port path from the root hub, interface number.
struct UsbInterfaceLocation {
  uint8_t bus = 0;
  std::vector<uint8_t> ports;
  int interface = 0;
  std::string sysfs_name;  // the interface's name under /sys/bus/usb/devices, e.g. "1-1:1.0"
};
// Parses a hidapi-libusb path: "1-1.4:1.0" (hidapi 0.13: bus-ports:config.interface).
bool parseHidapiLibusbPath(const std::string& path, UsbInterfaceLocation& out);

// Reads the HID report descriptor of an interface: from sysfs when the kernel's HID driver is
// bound (no detach/re-probe cycle), otherwise with GET_DESCRIPTOR (HID 1.11 §7.1.1) over libusb.
// Returns false and sets error.
bool readUsbHidReportDescriptor(const UsbInterfaceLocation& where, std::vector<uint8_t>& out,
                                std::string* error);

// libusb hotplug callbacks (when libusb has them) for one vendor; changed() reports whether a
// device arrived or left since the last call. Without hotplug support it always says false and
// callers fall back to polling.
class UsbHotplugWatcher {
 public:
  explicit UsbHotplugWatcher(uint16_t vendor = kWacomVendor);
  ~UsbHotplugWatcher();
  UsbHotplugWatcher(const UsbHotplugWatcher&) = delete;
  UsbHotplugWatcher& operator=(const UsbHotplugWatcher&) = delete;
  bool supported() const { return supported_; }
  bool changed();  // handles pending libusb events without blocking
  int arrivals() const { return arrivals_; }
  int departures() const { return departures_; }

 private:
  friend struct HotplugTrampoline;
  libusb_context* ctx_ = nullptr;
  int handle_ = 0;
  bool supported_ = false;
  bool changed_ = false;
  int arrivals_ = 0, departures_ = 0;
};

}  // namespace cb::usb
