// Picks and opens a pen backend by name: "auto" (evdev, the kernel driver's view), "evdev",
// "hidraw", "libusb" or "replay" (with a journal path).
#pragma once

#include <memory>
#include <string>

#include "drivers/core/pen_source.h"

namespace cb {

struct PenSourceOptions {
  std::string backend = "auto";
  std::string device;    // evdev node, hidapi path or journal file; empty: discover
  bool grab = false;     // evdev: exclusive grab
  bool realtime = true;  // replay pacing
  // hidraw/libusb: the folder of device files (config/devices; the app passes
  // configFile("devices")). Empty: none (every device gets hid-input's rules, no quirks).
  std::string device_dir;
  // hidraw/libusb: the input core's fuzz filter as evdev applies it (false: raw values).
  bool input_fuzz = true;
  // evdev/hidraw/libusb: read the device on a thread of its own, so a slow frame loses no
  // samples and a plugged tablet opens at once (threaded_pen_source.h). Replays never are.
  bool reader_thread = true;
};

// nullptr and `error` set for an unknown backend name or a replay without a file. Mistakes in
// the device files are written to stderr as FILE:LINE:COL (that file is skipped).
std::unique_ptr<PenSource> openPenSource(const PenSourceOptions& options, std::string* error);

}  // namespace cb
