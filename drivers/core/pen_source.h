// PenSource: one pen input path (evdev, hidapi hidraw/libusb, journal replay) seen the same way
// by the app. A missing or unplugged tablet is a connection state, never an exception or exit.
#pragma once

#include <string>
#include <vector>

#include "drivers/core/pen_sample.h"

namespace cb {

enum class PenConnection {
  kSearching,         // no pen device found yet (or it was unplugged): keep polling
  kConnected,         // reading samples
  kPermissionDenied,  // a pen exists but cannot be opened; statusMessage() names the fix
  kFinished,          // a replay reached its end
};

const char* penConnectionName(PenConnection c);

class PenSource {
 public:
  virtual ~PenSource() = default;
  // "evdev", "hidraw", "libusb", "replay".
  virtual const char* backendName() const = 0;
  // Waits up to timeout_ms (0: do not wait) for input or a hotplug change, and appends every
  // sample decoded meanwhile. Unplugging mid-stroke appends a proximity-out sample.
  virtual void poll(int timeout_ms, std::vector<PenSample>& out) = 0;
  // True when a poll(0, …) now would bring news (samples or a connection change) without
  // reading the device, from any thread: a long frame asks it between its slices and stops early
  // for a pen that just arrived (app/shell/kiosk/attract_screen.h). Sources read on the caller's own
  // thread cannot know without reading, and say false.
  virtual bool inputWaiting() const { return false; }
  virtual PenConnection connection() const = 0;
  // Valid while connected (and kept after a disconnect until the next device appears).
  virtual const PenDeviceInfo& deviceInfo() const = 0;
  // What the source is doing, for the UI: device path, or why it cannot open one.
  virtual std::string statusMessage() const = 0;
  // The serial number the connected device reports (evdev: the input device's `uniq`, which
  // usbhid fills from the USB iSerialNumber; hidapi: the HID serial string), or "" with
  // *why_none saying why there is none to report.
  virtual std::string serialNumber(std::string* why_none) const {
    if (why_none) *why_none = std::string(backendName()) + ": the backend reads no serial";
    return "";
  }
};

inline const char* penConnectionName(PenConnection c) {
  switch (c) {
    case PenConnection::kSearching:
      return "searching";
    case PenConnection::kConnected:
      return "connected";
    case PenConnection::kPermissionDenied:
      return "permission-denied";
    case PenConnection::kFinished:
      return "finished";
  }
  return "?";
}

// The udev rule shipped with cloudbrush; permission errors name it.
inline constexpr const char* kUdevRuleHint =
    "install the udev rule: sudo cp config/udev/70-cloudbrush-tablet.rules /etc/udev/rules.d/ "
    "&& sudo udevadm control --reload && sudo udevadm trigger, then add the kiosk user to group "
    "'input' (sudo usermod -aG input $USER) and log in again";

}  // namespace cb
