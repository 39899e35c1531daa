// PenSource over hidapi: raw HID reports decoded in user space, with the hidraw backend (kernel
// driver bound) or the libusb backend (no kernel driver; hidapi detaches it). The descriptor is
// read from the device (HIDIOCGRDESC on hidraw, GET_DESCRIPTOR over libusb), fixed up as the
// device files say, and with the device files' entry for the USB id picks the decoder: the
// Intuos4 protocol where the file says so, otherwise the generic layout-driven decoder with the
// kernel driver's rules. The input core's fuzz filter is applied as evdev applies it.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "drivers/core/pen_source.h"
#include "drivers/devices/device_database.h"
#include "drivers/hid/hid_pen_decoder.h"
#include "drivers/hid/hidapi_library.h"
#include "drivers/hid/input_fuzz_filter.h"
#include "drivers/hid/intuos4_decoder.h"

namespace cb::usb {
class UsbHotplugWatcher;
}

namespace cb::hid {

struct HidapiPenSourceOptions {
  HidapiBackend backend = HidapiBackend::kHidraw;
  uint16_t vendor = 0;  // 0: any vendor (a HID device is used only if it describes a pen)
  std::string path;     // a hidapi path to use; empty: discover
  // The device files (config/devices); null: no entries (hid-input's rules for everyone, no
  // Intuos4 protocol, no quirks).
  std::shared_ptr<const DeviceDatabase> devices;
  // The input core's fuzz filter with the fuzz of the device's entry, as evdev delivers values
  // (InputFuzzFilter). false: raw values.
  bool input_fuzz = true;
  // Set the tablet-mode feature report of the device's entry when it is not already set.
  bool switch_mode = true;
  // A pen in proximity that sends nothing for this long is taken out of proximity, as the
  // kernel's wacom driver does (wacom_idleprox_timeout) for firmware that may not send a
  // proximity-out report; the time comes from the device's entry (idle_proximity_timeout_ms;
  // hid-input has no such timer). false disables it.
  bool idle_proximity_timeout = true;
};

// Decoder chosen for a device: Intuos4 protocol or the descriptor-driven generic decoder.
using PenDecoder = std::variant<Intuos4Decoder, HidPenDecoder>;

struct HidPenDevice {
  std::string path;  // hidapi path
  uint16_t vendor = 0, product = 0;
  int interface = -1;
  std::string name;
  std::string serial;  // the HID serial string ("" when the device reports none)
  PenDeviceInfo info{};
  std::string protocol;  // "intuos4" or "generic"
  DeviceEntry entry;     // the device files' entry (a default one when there is none)
  bool has_entry = false;
  int fixups_applied = 0;  // report-descriptor fix-ups that changed the descriptor
  uint8_t mode_report_id = 0;
  std::vector<uint8_t> descriptor;  // the HID report descriptor as read from the device
  std::string error;                // why this HID device is not usable as a pen
  bool permission_denied = false;
};

// Lists HID devices of `vendor` (0: all) through a backend, with the pen each one describes.
std::vector<HidPenDevice> findHidPens(HidapiLibrary& lib, uint16_t vendor,
                                      const DeviceDatabase* devices);
// Builds the decoder for a device from its report descriptor and its entry in `devices` (may be
// null); also used by tests and benches.
bool makePenDecoder(const DeviceDatabase* devices, uint16_t vendor, uint16_t product,
                    const std::string& name, const std::vector<uint8_t>& descriptor,
                    HidPenDevice& device, std::unique_ptr<PenDecoder>& decoder);
DecodeResult decodeReport(PenDecoder& decoder, const uint8_t* report, size_t n, int64_t t_ns,
                          PenSample& out);

class HidapiPenSource final : public PenSource {
 public:
  explicit HidapiPenSource(HidapiPenSourceOptions options);
  ~HidapiPenSource() override;
  HidapiPenSource(const HidapiPenSource&) = delete;
  HidapiPenSource& operator=(const HidapiPenSource&) = delete;

  const char* backendName() const override { return hidapiBackendName(options_.backend); }
  void poll(int timeout_ms, std::vector<PenSample>& out) override;
  PenConnection connection() const override { return connection_; }
  const PenDeviceInfo& deviceInfo() const override { return device_.info; }
  std::string statusMessage() const override { return status_; }
  std::string serialNumber(std::string* why_none) const override;
  const HidPenDevice& device() const { return device_; }
  uint64_t rejectedReports() const { return rejected_; }
  const std::string& lastRejection() const { return last_rejection_; }

 private:
  void tryOpen();
  void closeDevice(std::vector<PenSample>* out);
  void ensureTabletMode();

  HidapiPenSourceOptions options_;
  std::shared_ptr<HidapiLibrary> lib_;
  std::unique_ptr<usb::UsbHotplugWatcher> hotplug_;
  hid_device* dev_ = nullptr;
  HidPenDevice device_;
  std::unique_ptr<PenDecoder> decoder_;
  InputFuzzFilter fuzz_;
  PenConnection connection_ = PenConnection::kSearching;
  std::string status_;
  int64_t next_scan_ns_ = 0;
  uint64_t rejected_ = 0;
  int64_t last_report_ns_ = 0;
  bool pen_in_proximity_ = false;
  std::string last_rejection_;
};

}  // namespace cb::hid
