// hidapi's two Linux backends (libhidapi-hidraw: through the kernel's hidraw nodes, needs the
// kernel driver bound; libhidapi-libusb: straight to the USB device, kernel driver detached)
// export the same symbols, so one process cannot link both. Each is loaded here with dlopen into
// its own function table.
#pragma once

#include <hidapi/hidapi.h>

#include <memory>
#include <string>

namespace cb::hid {

enum class HidapiBackend { kHidraw, kLibusb };
const char* hidapiBackendName(HidapiBackend b);  // "hidraw" / "libusb"

struct HidapiLibrary {
  HidapiBackend backend{};
  void* handle = nullptr;
  int (*init)() = nullptr;
  int (*exit)() = nullptr;
  hid_device_info* (*enumerate)(unsigned short, unsigned short) = nullptr;
  void (*free_enumeration)(hid_device_info*) = nullptr;
  hid_device* (*open_path)(const char*) = nullptr;
  void (*close)(hid_device*) = nullptr;
  int (*read_timeout)(hid_device*, unsigned char*, size_t, int) = nullptr;
  int (*get_feature_report)(hid_device*, unsigned char*, size_t) = nullptr;
  int (*send_feature_report)(hid_device*, const unsigned char*, size_t) = nullptr;
  const wchar_t* (*error)(hid_device*) = nullptr;

  ~HidapiLibrary();
};

// Loads (once per process) and initialises a backend; nullptr and `error` set on failure.
std::shared_ptr<HidapiLibrary> loadHidapi(HidapiBackend backend, std::string* error);

std::string narrow(const wchar_t* s);

}  // namespace cb::hid
