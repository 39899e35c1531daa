// A real USB HID device on a virtual bus: dummy_hcd (host and device controller in one) +
// libcomposite + usb_f_hid configured through configfs. The host side enumerates it like a
// plugged-in tablet (usbhid + wacom bind, libusb sees it); reports are written to /dev/hidgN.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace cb::hil {

struct GadgetConfig {
  uint16_t vendor = 0x056A, product = 0x0357;
  std::string manufacturer = "Wacom Co.,Ltd.", product_name = "Intuos Pro M", serial = "CBHIL0001";
  std::vector<uint8_t> report_descriptor;
  uint16_t report_length = 64;
};

class UsbGadget {
 public:
  ~UsbGadget();
  // Creates the gadget under /sys/kernel/config/usb_gadget/NAME (configfs must be mounted).
  bool create(const std::string& name, const GadgetConfig& config, std::string* error);
  bool bind(std::string* error);    // attach to the first UDC (plug in)
  bool unbind(std::string* error);  // detach (unplug)
  // Writes one report (ID byte first) to /dev/hidg0; waits up to timeout_ms for the host.
  bool send(const std::vector<uint8_t>& report, int timeout_ms, std::string* error);
  void remove();

 private:
  std::string dir_;
  int hidg_fd_ = -1;
};

}  // namespace cb::hil
