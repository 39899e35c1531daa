// `cloudbrush devices [--watch]`: lists what every backend sees (evdev nodes, hidapi-hidraw and
// hidapi-libusb interfaces of any vendor, libusb identity of Wacom devices) and says which are
// pens, which are not and why, and which this user cannot open; or prints live samples like
// `libinput debug-events`.
#include <grp.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/core/config_paths.h"
#include "drivers/core/clock.h"
#include "drivers/core/journal.h"
#include "drivers/devices/device_file.h"
#include "drivers/devices/udev_rules.h"
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
      "                          [--count N] [--seconds S] [--record FILE]\n"
      "       cloudbrush devices --udev-rules\n\n"
      "Lists pen tablets: backend, name, USB id, ranges and resolutions.\n\n"
      "  --udev-rules     print the udev rules that open every device the device files name\n"
      "                   to group input (config/udev/70-cloudbrush-tablet.rules is this)\n"
      "  --watch          print live samples from one pen (Ctrl-C stops)\n"
      "  --backend NAME   auto (evdev), evdev, hidraw, libusb, replay (default auto)\n"
      "  --device PATH    event node, hidapi path or, for replay, a journal file\n"
      "  --grab           evdev: grab the pen exclusively while watching\n"
      "  --raw            hidraw/libusb: no input-core fuzz filter (evdev always has it)\n"
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

// What one backend saw, for the closing summary.
struct BackendTally {
  std::string name, how;
  std::string unavailable;  // why the backend could not be tried at all
  int seen = 0, pens = 0, not_pens = 0, cannot_open = 0, denied = 0;
  std::vector<std::string> denied_ids;  // hidraw: vid:pid of devices this user cannot open
};

bool inGroup(const char* name) {
  const group* g = getgrnam(name);
  if (!g) return false;
  if (getegid() == g->gr_gid) return true;
  gid_t groups[256];
  const int n = getgroups(256, groups);
  for (int i = 0; i < n; ++i)
    if (groups[i] == g->gr_gid) return true;
  return false;
}

// Every backend in turn, and what it saw: pens, devices that are not pens (and why), nodes
// this user cannot open (and the error). Ends with a summary of what was tried and, when
// something was closed to this user, how to open it.
// The evdev nodes: each said (a pen, not a pen, cannot open) and tallied.
BackendTally surveyEvdevBackend() {
  BackendTally ev;
  ev.name = "evdev";
  ev.how = "the kernel driver's input nodes";
  const EvdevSurvey survey = surveyEvdevNodes();
  if (!survey.dir_error.empty()) {
    std::printf("evdev   cannot list %s: %s\n", survey.dir.c_str(), survey.dir_error.c_str());
    ev.unavailable = "cannot list " + survey.dir + ": " + survey.dir_error;
    if (!survey.dir_permission_denied)
      ev.unavailable += " (no input devices at all: a container, or a machine without evdev)";
    ev.denied += survey.dir_permission_denied ? 1 : 0;
  } else {
    std::printf("evdev   %s: %zu event node(s)\n", survey.dir.c_str(), survey.nodes.size());
  }
  ev.seen = static_cast<int>(survey.nodes.size());
  for (const EvdevNodeReport& n : survey.nodes) {
    switch (n.kind) {
      case EvdevNodeKind::kPen:
        printInfo("evdev", n.path, n.info, "");
        ++ev.pens;
        break;
      case EvdevNodeKind::kNotAPen:
        std::printf("        %-22s not a pen: '%s' is %s\n", n.path.c_str(), n.name.c_str(),
                    n.detail.c_str());
        ++ev.not_pens;
        break;
      case EvdevNodeKind::kCannotOpen:
        std::printf("        %-22s cannot open: %s\n", n.path.c_str(), n.detail.c_str());
        ++ev.cannot_open;
        ev.denied += n.permission_denied ? 1 : 0;
        break;
    }
  }
  return ev;
}

// One hidapi backend's HID interfaces: each said and tallied.
BackendTally surveyHidapiBackend(hid::HidapiBackend b, const DeviceDatabase* database) {
  BackendTally t;
  t.name = hid::hidapiBackendName(b);
  t.how = b == hid::HidapiBackend::kHidraw ? "hidapi, raw reports beside the kernel driver"
                                           : "hidapi over libusb, kernel driver detached";
  std::string error;
  auto lib = hid::loadHidapi(b, &error);
  if (!lib) {
    std::printf("%-7s unavailable: %s\n", hid::hidapiBackendName(b), error.c_str());
    t.unavailable = error;
    return t;
  }
  const std::vector<hid::HidPenDevice> devices =
      hid::findHidPens(*lib, 0, database);  // every vendor
  std::printf("%-7s %zu HID interface(s)\n", hid::hidapiBackendName(b), devices.size());
  t.seen = static_cast<int>(devices.size());
  for (const hid::HidPenDevice& d : devices) {
    if (d.permission_denied) {
      ++t.denied;
      char id[16];
      std::snprintf(id, sizeof id, "%04x:%04x", d.vendor, d.product);
      t.denied_ids.push_back(id);
    }
    if (d.protocol.empty()) {
      std::printf("        %-22s %04x:%04x %s (interface %d): %s%s\n", d.path.c_str(), d.vendor,
                  d.product, d.name.c_str(), d.interface,
                  d.descriptor.empty() ? "cannot read the report descriptor: " : "not a pen: ",
                  d.error.c_str());
      ++(d.descriptor.empty() ? t.cannot_open : t.not_pens);
      continue;
    }
    std::string extra = "  [" + d.protocol + " protocol";
    if (d.has_entry) extra += ", " + d.entry.family + " (" + d.entry.where + ")";
    printInfo(hid::hidapiBackendName(b), d.path, d.info, extra + "]");
    ++t.pens;
  }
  return t;
}

int listDevices() {
  const std::string device_dir = configFile("devices");
  const DeviceFileLoad device_files = loadDeviceDirectory(device_dir);
  std::printf("device files: %zu loaded from %s (%zu entries)\n",
              device_files.database->files().size(), device_dir.c_str(),
              device_files.database->entries().size());
  for (const std::string& e : device_files.errors) std::printf("        error: %s\n", e.c_str());

  std::vector<BackendTally> tally;
  tally.push_back(surveyEvdevBackend());
  for (hid::HidapiBackend b : {hid::HidapiBackend::kHidraw, hid::HidapiBackend::kLibusb})
    tally.push_back(surveyHidapiBackend(b, device_files.database.get()));
  for (const usb::UsbDeviceIdentity& u : usb::listUsbDevices(usb::kWacomVendor)) {
    std::printf("usb     bus %03d addr %03d       %04x:%04x  %s %s serial '%s'%s\n", u.bus,
                u.address, u.vendor, u.product, u.manufacturer.c_str(), u.product_name.c_str(),
                u.serial.c_str(), u.opened ? "" : (" (" + u.open_error + ")").c_str());
  }

  int found = 0, denied = 0;
  std::printf("\ntried:\n");
  for (const BackendTally& t : tally) {
    found += t.pens;
    denied += t.denied;
    if (!t.unavailable.empty()) {
      std::printf("  %-7s (%s): not tried: %s\n", t.name.c_str(), t.how.c_str(),
                  t.unavailable.c_str());
      continue;
    }
    std::printf(
        "  %-7s (%s): %d seen, %d pen(s), %d not a pen, %d could not be opened%s\n", t.name.c_str(),
        t.how.c_str(), t.seen, t.pens, t.not_pens, t.cannot_open,
        t.denied ? (" (" + std::to_string(t.denied) + " for lack of permission)").c_str() : "");
  }
  if (found == 0)
    std::printf("no pen tablet found%s\n",
                denied == 0 ? ": nothing was closed to this user; plug the tablet in, or check "
                              "`dmesg` for a driver that refused it"
                            : "");
  if (denied > 0) {
    std::printf("%d device(s) could not be opened by this user. To fix:\n  %s\n", denied,
                kUdevRuleHint);
    std::printf(
        "  this user is %sin group 'input'%s\n", inGroup("input") ? "" : "NOT ",
        inGroup("input") ? " (the rule may not be installed, or udev has not applied it)" : "");
    for (const BackendTally& t : tally)
      for (const std::string& id : t.denied_ids) {
        const unsigned vendor = unsigned(std::strtoul(id.substr(0, 4).c_str(), nullptr, 16));
        const unsigned product = unsigned(std::strtoul(id.substr(5, 4).c_str(), nullptr, 16));
        if (device_files.database->find(uint16_t(vendor), uint16_t(product))) continue;
        std::printf(
            "  %s %s: no device file names it, so the shipped rule does not open it; add a "
            "file to %s and install the rules `cloudbrush devices --udev-rules` prints, or add: "
            "SUBSYSTEM==\"hidraw\", ATTRS{idVendor}==\"%s\", GROUP=\"input\", "
            "MODE=\"0660\"\n",
            t.name.c_str(), id.c_str(), device_dir.c_str(), id.substr(0, 4).c_str());
      }
  }
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
  o.device_dir = configFile("devices");
  o.input_fuzz = !args.has("raw");
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
  Args args(argc, argv, {"help", "watch", "grab", "raw", "udev-rules"});
  if (args.has("help")) {
    printHelp();
    return 0;
  }
  auto unknown = args.unknown({"help", "watch", "grab", "raw", "udev-rules", "backend", "device",
                               "count", "seconds", "record"});
  if (!unknown.empty()) {
    std::fprintf(stderr, "cloudbrush devices: unknown option %s (see --help)\n",
                 unknown.front().c_str());
    return 2;
  }
  if (args.has("udev-rules")) {
    const DeviceFileLoad files = loadDeviceDirectory(configFile("devices"));
    for (const std::string& e : files.errors) std::fprintf(stderr, "error: %s\n", e.c_str());
    std::fputs(udevRules(*files.database).c_str(), stdout);
    return files.errors.empty() ? 0 : 1;
  }
  return args.has("watch") ? watch(args) : listDevices();
}

}  // namespace cb
