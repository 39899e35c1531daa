// `cloudbrush devices [--watch]`: lists what every backend sees (evdev nodes, hidapi-hidraw and
// hidapi-libusb interfaces of any vendor, libusb identity of Wacom devices) and says which are
// pens, which are not and why, and which this user cannot open; or prints live samples like
// `libinput debug-events`.
#include <csignal>
#include <cstdio>
#include <string>
#include <vector>

#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "drivers/core/clock.h"
#include "drivers/core/journal.h"
#include "drivers/evdev/evdev_node_survey.h"
#include "drivers/hid/hidapi_pen_source.h"
#include "drivers/open_pen_source.h"
#include "drivers/usb/usb_devices.h"

namespace cb {
namespace {

volatile std::sig_atomic_t g_stop = 0;

void printHelp() {
  std::printf(
      "usage: cloudbrush devices [--watch] [--backend NAME] [--device PATH] [--grab]\n"
      "                          [--count N] [--seconds S] [--record FILE]\n\n"
      "Lists pen tablets: backend, name, USB id, ranges and resolutions.\n\n"
      "  --watch          print live samples from one pen (Ctrl-C stops)\n"
      "  --backend NAME   auto (evdev), evdev, hidraw, libusb, replay (default auto)\n"
      "  --device PATH    event node, hidapi path or, for replay, a journal file\n"
      "  --grab           evdev: grab the pen exclusively while watching\n"
      "  --count N        stop after N samples\n"
      "  --seconds S      stop after S seconds\n"
      "  --record FILE    also write the device and its samples to a journal (replayable with\n"
      "                   --backend replay --device FILE)\n\n"
      "A missing tablet is not an error: --watch waits for one to be plugged in.\n");
}

void printInfo(const char* backend, const std::string& where, const PenDeviceInfo& d,
               const std::string& extra) {
  std::printf("%-7s %-22s %04x:%04x  %s%s\n", backend, where.c_str(), d.usb_vendor, d.usb_product,
              d.name, extra.c_str());
  std::printf("        x 0..%d (%.0f/mm = %.1f mm)  y 0..%d (%.0f/mm = %.1f mm)  pressure 0..%d\n",
              d.x_max, d.x_res, d.x_res > 0 ? d.x_max / d.x_res : 0.0, d.y_max, d.y_res,
              d.y_res > 0 ? d.y_max / d.y_res : 0.0, d.pressure_max);
  std::printf("        tilt %d..%d (%.3f/deg)  distance 0..%d\n", d.tilt_min, d.tilt_max,
              d.tilt_res, d.distance_max);
}

// Every backend in turn, and what it saw: pens, devices that are not pens (and why), nodes
// this user cannot open (and the error). Ends with what to do when no pen was found.
int listDevices() {
  int found = 0, denied = 0;
  const EvdevSurvey survey = surveyEvdevNodes();
  if (!survey.dir_error.empty()) {
    std::printf("evdev   cannot list %s: %s\n", survey.dir.c_str(), survey.dir_error.c_str());
    denied += survey.dir_permission_denied ? 1 : 0;
  } else {
    std::printf("evdev   %s: %zu event node(s)\n", survey.dir.c_str(), survey.nodes.size());
  }
  for (const EvdevNodeReport& n : survey.nodes) {
    switch (n.kind) {
      case EvdevNodeKind::kPen:
        printInfo("evdev", n.path, n.info, "");
        ++found;
        break;
      case EvdevNodeKind::kNotAPen:
        std::printf("        %-22s not a pen: '%s' is %s\n", n.path.c_str(), n.name.c_str(),
                    n.detail.c_str());
        break;
      case EvdevNodeKind::kCannotOpen:
        std::printf("        %-22s cannot open: %s\n", n.path.c_str(), n.detail.c_str());
        denied += n.permission_denied ? 1 : 0;
        break;
    }
  }
  for (hid::HidapiBackend b : {hid::HidapiBackend::kHidraw, hid::HidapiBackend::kLibusb}) {
    std::string error;
    auto lib = hid::loadHidapi(b, &error);
    if (!lib) {
      std::printf("%-7s unavailable: %s\n", hid::hidapiBackendName(b), error.c_str());
      continue;
    }
    const std::vector<hid::HidPenDevice> devices = hid::findHidPens(*lib, 0);  // every vendor
    std::printf("%-7s %zu HID interface(s)\n", hid::hidapiBackendName(b), devices.size());
    for (const hid::HidPenDevice& d : devices) {
      if (d.permission_denied) ++denied;
      if (d.protocol.empty()) {
        std::printf("        %-22s %04x:%04x %s (interface %d): %s%s\n", d.path.c_str(), d.vendor,
                    d.product, d.name.c_str(), d.interface,
                    d.descriptor.empty() ? "cannot read the report descriptor: " : "not a pen: ",
                    d.error.c_str());
        continue;
      }
      printInfo(hid::hidapiBackendName(b), d.path, d.info, "  [" + d.protocol + " protocol]");
      ++found;
    }
  }
  for (const usb::UsbDeviceIdentity& u : usb::listUsbDevices(usb::kWacomVendor)) {
    std::printf("usb     bus %03d addr %03d       %04x:%04x  %s %s serial '%s'%s\n", u.bus,
                u.address, u.vendor, u.product, u.manufacturer.c_str(), u.product_name.c_str(),
                u.serial.c_str(), u.opened ? "" : (" (" + u.open_error + ")").c_str());
  }
  if (found == 0) {
    std::printf("no pen tablet found (tried evdev, hidraw and libusb)\n");
    if (denied == 0)
      std::printf(
          "nothing was closed to this user: plug the tablet in, or check `dmesg` for a "
          "driver that refused it\n");
  }
  if (denied > 0)
    std::printf("%d device(s) could not be opened by this user: %s\n", denied, kUdevRuleHint);
  return 0;
}

std::string buttonNames(uint32_t b) {
  std::string s;
  if (b & kPenTip) s += "tip ";
  if (b & kPenStylus1) s += "stylus ";
  if (b & kPenStylus2) s += "stylus2 ";
  if (s.empty()) return "-";
  s.pop_back();
  return s;
}

int watch(Args& args) {
  PenSourceOptions o;
  o.backend = args.get("backend", "auto");
  o.device = args.get("device", "");
  o.grab = args.has("grab");
  const long count = args.getInt("count", 0);
  const double seconds = args.getDouble("seconds", 0.0);
  if (!args.error().empty()) {
    std::fprintf(stderr, "cloudbrush devices: %s\n", args.error().c_str());
    return 2;
  }
  std::string error;
  std::unique_ptr<PenSource> src = openPenSource(o, &error);
  if (!src) {
    std::fprintf(stderr, "cloudbrush devices: %s\n", error.c_str());
    return 2;
  }
  JournalWriter journal;
  const std::string record = args.get("record", "");
  if (!record.empty() && !journal.open(record)) {
    std::fprintf(stderr, "cloudbrush devices: %s\n", journal.error().c_str());
    return 1;
  }
  std::signal(SIGINT, [](int) { g_stop = 1; });
  MonotonicClock clock;
  const int64_t start = clock.nowNs();
  PenConnection last_state = PenConnection::kFinished;
  std::string last_status;
  long printed = 0;
  int64_t t0 = -1;
  bool was_in = false;
  std::vector<PenSample> samples;
  while (!g_stop) {
    if (seconds > 0 && clock.nowNs() - start > static_cast<int64_t>(seconds * 1e9)) break;
    samples.clear();
    src->poll(100, samples);
    if (src->connection() != last_state || src->statusMessage() != last_status) {
      last_state = src->connection();
      last_status = src->statusMessage();
      std::printf("-- %s %s: %s\n", src->backendName(), penConnectionName(last_state),
                  last_status.c_str());
      if (last_state == PenConnection::kConnected) {
        printInfo(src->backendName(), "", src->deviceInfo(), "");
        if (!record.empty()) {
          const auto info = encodeDeviceInfo(src->deviceInfo());
          journal.append(JournalRecordType::kDevice, clock.nowNs(), info.data(), info.size());
        }
      }
      std::fflush(stdout);
    }
    for (const PenSample& s : samples) {
      if (t0 < 0) t0 = s.t_ns;  // times relative to the first sample (replays keep theirs)
      const char* event = s.in_proximity ? (was_in ? "motion " : "prox-in") : "prox-out";
      was_in = s.in_proximity;
      std::printf(
          "%+10.3fs %-8s %-6s id %#06x serial %#010llx  %8.2f %8.2f mm  p %.3f  tilt "
          "%6.1f %6.1f  dist %.3f  %s\n",
          (s.t_ns - t0) / 1e9, event, s.tool == PenTool::kEraser ? "eraser" : "pen", s.tool_id,
          static_cast<unsigned long long>(s.tool_serial), s.x_mm, s.y_mm, s.pressure, s.tilt_x_deg,
          s.tilt_y_deg, s.distance, buttonNames(s.buttons).c_str());
      if (!record.empty()) journal.appendPenSample(s);
      if (count > 0 && ++printed >= count) g_stop = 1;
    }
    std::fflush(stdout);
    if (src->connection() == PenConnection::kFinished) break;
  }
  return 0;
}

}  // namespace

int commandDevices(int argc, char** argv) {
  Args args(argc, argv, {"help", "watch", "grab"});
  if (args.has("help")) {
    printHelp();
    return 0;
  }
  auto unknown =
      args.unknown({"help", "watch", "grab", "backend", "device", "count", "seconds", "record"});
  if (!unknown.empty()) {
    std::fprintf(stderr, "cloudbrush devices: unknown option %s (see --help)\n",
                 unknown.front().c_str());
    return 2;
  }
  return args.has("watch") ? watch(args) : listDevices();
}

}  // namespace cb
