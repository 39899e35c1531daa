#include "drivers/usb/usb_devices.h"

#include <dirent.h>
#include <libusb.h>

#include <cstdio>
#include <fstream>
#include <iterator>

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

bool parseHidapiLibusbPath(const std::string& path, UsbInterfaceLocation& out) {
  // bus "-" port ("." port)* ":" config "." interface, all decimal
  size_t dash = path.find('-'), colon = path.find(':');
  if (dash == std::string::npos || colon == std::string::npos || colon < dash) return false;
  auto number = [](const std::string& s, int& v) {
    if (s.empty() || s.size() > 3 || s.find_first_not_of("0123456789") != std::string::npos)
      return false;
    v = std::stoi(s);
    return v <= 255;
  };
  int v = 0;
  if (!number(path.substr(0, dash), v)) return false;
  out.bus = static_cast<uint8_t>(v);
  out.ports.clear();
  std::string ports = path.substr(dash + 1, colon - dash - 1);
  size_t start = 0;
  while (true) {
    size_t dot = ports.find('.', start);
    if (!number(ports.substr(start, dot - start), v) || out.ports.size() >= 7) return false;
    out.ports.push_back(static_cast<uint8_t>(v));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  std::string tail = path.substr(colon + 1);
  size_t dot = tail.find('.');
  if (dot == std::string::npos || !number(tail.substr(0, dot), v) ||
      !number(tail.substr(dot + 1), v))
    return false;
  out.interface = v;
  out.sysfs_name = path;
  return true;
}

namespace {

// /sys/bus/usb/devices/<interface>/<hid device>/report_descriptor, present while usbhid is bound.
bool readSysfsReportDescriptor(const std::string& interface_name, std::vector<uint8_t>& out) {
  if (interface_name.empty() || interface_name.find('/') != std::string::npos) return false;
  const std::string dir = "/sys/bus/usb/devices/" + interface_name;
  DIR* d = opendir(dir.c_str());
  if (!d) return false;
  bool ok = false;
  while (dirent* e = readdir(d)) {
    unsigned bus, vid, pid, seq;
    char tail;
    if (std::sscanf(e->d_name, "%4x:%4x:%4x.%4x%c", &bus, &vid, &pid, &seq, &tail) != 4) continue;
    std::ifstream in(dir + "/" + e->d_name + "/report_descriptor", std::ios::binary);
    std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                               std::istreambuf_iterator<char>());
    if (!bytes.empty()) {
      out = std::move(bytes);
      ok = true;
      break;
    }
  }
  closedir(d);
  return ok;
}

}  // namespace

bool readUsbHidReportDescriptor(const UsbInterfaceLocation& where, std::vector<uint8_t>& out,
                                std::string* error) {
  if (readSysfsReportDescriptor(where.sysfs_name, out)) return true;
  const int interface = where.interface;
  libusb_context* ctx = nullptr;
  if (libusb_init(&ctx) != 0) {
    if (error) *error = "libusb_init failed";
    return false;
  }
  bool ok = false;
  libusb_device** list = nullptr;
  ssize_t n = libusb_get_device_list(ctx, &list);
  libusb_device* dev = nullptr;
  for (ssize_t i = 0; i < n; ++i) {
    uint8_t ports[8];
    int np = libusb_get_port_numbers(list[i], ports, sizeof ports);
    if (libusb_get_bus_number(list[i]) == where.bus && np > 0 &&
        std::vector<uint8_t>(ports, ports + np) == where.ports)
      dev = list[i];
  }
  libusb_device_handle* h = nullptr;
  int rc = dev ? libusb_open(dev, &h) : LIBUSB_ERROR_NO_DEVICE;
  if (rc != 0) {
    if (error)
      *error = "cannot open USB device on bus " + std::to_string(where.bus) + ": " +
               libusb_strerror(static_cast<libusb_error>(rc));
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
