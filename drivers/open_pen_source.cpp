#include "drivers/open_pen_source.h"

#include <cstdio>

#include "drivers/core/threaded_pen_source.h"
#include "drivers/devices/device_file.h"
#include "drivers/evdev/evdev_pen_source.h"
#include "drivers/hid/hidapi_pen_source.h"
#include "drivers/replay/replay_pen_source.h"

namespace cb {

namespace {

// A tablet is read on a thread of its own unless asked otherwise (threaded_pen_source.h).
std::unique_ptr<PenSource> live(std::unique_ptr<PenSource> backend, const PenSourceOptions& o) {
  if (!o.reader_thread) return backend;
  return std::make_unique<ThreadedPenSource>(std::move(backend));
}

}  // namespace

std::unique_ptr<PenSource> openPenSource(const PenSourceOptions& o, std::string* error) {
  if (o.backend == "auto" || o.backend == "evdev") {
    EvdevPenSourceOptions e;
    e.device_path = o.device;
    e.grab = o.grab;
    return live(std::make_unique<EvdevPenSource>(e), o);
  }
  if (o.backend == "hidraw" || o.backend == "libusb") {
    hid::HidapiPenSourceOptions h;
    h.backend = o.backend == "hidraw" ? hid::HidapiBackend::kHidraw : hid::HidapiBackend::kLibusb;
    h.path = o.device;
    h.input_fuzz = o.input_fuzz;
    if (!o.device_dir.empty()) {
      DeviceFileLoad load = loadDeviceDirectory(o.device_dir);
      for (const std::string& e : load.errors) std::fprintf(stderr, "cloudbrush: %s\n", e.c_str());
      h.devices = load.database;
    }
    return live(std::make_unique<hid::HidapiPenSource>(h), o);
  }
  if (o.backend == "replay") {
    if (o.device.empty()) {
      if (error) *error = "the replay backend needs a journal file (--device FILE)";
      return nullptr;
    }
    ReplayOptions r;
    r.realtime = o.realtime;
    return std::make_unique<ReplayPenSource>(o.device, r);
  }
  if (error)
    *error = "unknown pen backend '" + o.backend + "' (auto, evdev, hidraw, libusb, replay)";
  return nullptr;
}

}  // namespace cb
