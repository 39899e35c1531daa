#include "drivers/usb/usb_devices.h"

#include <libusb.h>

namespace cb::usb {
namespace {

std::string stringDescriptor(libusb_device_handle* h, uint8_t index) {
  if (index == 0) return {};
  unsigned char buf[256];
  int n = libusb_get_string_descriptor_ascii(h, index, buf, sizeof buf);
  return n > 0 ? std::string(reinterpret_cast<char*>(buf), static_cast<size_t>(n)) : std::string();
}

}  // namespace

std::vector<UsbDeviceIdentity> listUsbDevices(uint16_t vendor) {
  std::vector<UsbDeviceIdentity> out;
  libusb_context* ctx = nullptr;
  if (libusb_init(&ctx) != 0) return out;
  libusb_device** list = nullptr;
  ssize_t n = libusb_get_device_list(ctx, &list);
  for (ssize_t i = 0; i < n; ++i) {
    libusb_device_descriptor dd;
    if (libusb_get_device_descriptor(list[i], &dd) != 0) continue;
    if (vendor != 0 && dd.idVendor != vendor) continue;
    UsbDeviceIdentity id;
    id.vendor = dd.idVendor;
    id.product = dd.idProduct;
    id.bus = libusb_get_bus_number(list[i]);
    id.address = libusb_get_device_address(list[i]);
    libusb_device_handle* h = nullptr;
    int rc = libusb_open(list[i], &h);
    if (rc == 0) {
      id.opened = true;
      id.manufacturer = stringDescriptor(h, dd.iManufacturer);
      id.product_name = stringDescriptor(h, dd.iProduct);
      id.serial = stringDescriptor(h, dd.iSerialNumber);
      libusb_close(h);
    } else {
      id.open_error = libusb_strerror(static_cast<libusb_error>(rc));
    }
    out.push_back(id);
  }
  if (list) libusb_free_device_list(list, 1);
  libusb_exit(ctx);
  return out;
}

bool readUsbHidReportDescriptor(uint8_t bus, uint8_t address, int interface,
                                std::vector<uint8_t>& out, std::string* error) {
  libusb_context* ctx = nullptr;
  if (libusb_init(&ctx) != 0) {
    if (error) *error = "libusb_init failed";
    return false;
  }
  bool ok = false;
  libusb_device** list = nullptr;
  ssize_t n = libusb_get_device_list(ctx, &list);
  libusb_device* dev = nullptr;
  for (ssize_t i = 0; i < n; ++i)
    if (libusb_get_bus_number(list[i]) == bus && libusb_get_device_address(list[i]) == address)
      dev = list[i];
  libusb_device_handle* h = nullptr;
  int rc = dev ? libusb_open(dev, &h) : LIBUSB_ERROR_NO_DEVICE;
  if (rc != 0) {
    if (error)
      *error = "cannot open USB device " + std::to_string(bus) + ":" + std::to_string(address) +
               ": " + libusb_strerror(static_cast<libusb_error>(rc));
  } else {
    libusb_set_auto_detach_kernel_driver(h, 1);
    rc = libusb_claim_interface(h, interface);
    if (rc != 0) {
      if (error)
        *error = std::string("cannot claim interface: ") +
                 libusb_strerror(static_cast<libusb_error>(rc));
    } else {
      unsigned char buf[4096];
      // Standard request, IN, recipient interface: GET_DESCRIPTOR, type 0x22 (HID report).
      rc = libusb_control_transfer(h,
                                   static_cast<uint8_t>(LIBUSB_ENDPOINT_IN) |
                                       static_cast<uint8_t>(LIBUSB_RECIPIENT_INTERFACE),
                                   LIBUSB_REQUEST_GET_DESCRIPTOR, 0x2200,
                                   static_cast<uint16_t>(interface), buf, sizeof buf, 1000);
      if (rc > 0) {
        out.assign(buf, buf + rc);
        ok = true;
      } else if (error) {
        *error = std::string("GET_DESCRIPTOR(report) failed: ") +
                 libusb_strerror(static_cast<libusb_error>(rc));
      }
      libusb_release_interface(h, interface);
    }
    libusb_close(h);
  }
  if (list) libusb_free_device_list(list, 1);
  libusb_exit(ctx);
  return ok;
}

struct HotplugTrampoline {
  static int LIBUSB_CALL callback(libusb_context*, libusb_device*, libusb_hotplug_event event,
                                  void* user) {
    auto* w = static_cast<UsbHotplugWatcher*>(user);
    w->changed_ = true;
    if (event == LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED)
      ++w->arrivals_;
    else
      ++w->departures_;
    return 0;
  }
};

UsbHotplugWatcher::UsbHotplugWatcher(uint16_t vendor) {
  if (libusb_init(&ctx_) != 0) {
    ctx_ = nullptr;
    return;
  }
  if (!libusb_has_capability(LIBUSB_CAP_HAS_HOTPLUG)) return;
  int rc = libusb_hotplug_register_callback(
      ctx_,
      static_cast<libusb_hotplug_event>(LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED |
                                        LIBUSB_HOTPLUG_EVENT_DEVICE_LEFT),
      LIBUSB_HOTPLUG_NO_FLAGS, vendor ? vendor : LIBUSB_HOTPLUG_MATCH_ANY, LIBUSB_HOTPLUG_MATCH_ANY,
      LIBUSB_HOTPLUG_MATCH_ANY, &HotplugTrampoline::callback, this, &handle_);
  supported_ = rc == LIBUSB_SUCCESS;
}

UsbHotplugWatcher::~UsbHotplugWatcher() {
  if (!ctx_) return;
  if (supported_) libusb_hotplug_deregister_callback(ctx_, handle_);
  libusb_exit(ctx_);
}

bool UsbHotplugWatcher::changed() {
  if (!supported_) return false;
  timeval zero{0, 0};
  libusb_handle_events_timeout_completed(ctx_, &zero, nullptr);
  bool c = changed_;
  changed_ = false;
  return c;
}

}  // namespace cb::usb
