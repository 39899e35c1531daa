#include "tests/hil/tablet/uclogic_phase.h"

#include <dirent.h>
#include <linux/usb/ch9.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "drivers/core/clock.h"
#include "drivers/core/pen_units.h"
#include "drivers/evdev/evdev_pen_source.h"
#include "drivers/hid/hid_pen_layout.h"
#include "drivers/hid/hid_report_descriptor.h"
#include "drivers/hid/hidapi_pen_source.h"
#include "drivers/usb/usb_devices.h"
#include "tests/hil/tablet/gadgetfs_device.h"
#include "tests/hil/tablet/hil_checks.h"
#include "tests/hil/tablet/hil_devices.h"
#include "tests/hil/tablet/pen_script.h"
#include "tests/hil/tablet/uclogic_models.h"

namespace cb::hil {
namespace {

// The pen part of the common script (the v2 pen has no eraser end and no distance), tilts
// within the template's -60..60, no serial or tool id (the pen reports none), and a stroke to
// the far corner where both axes need their high byte. Ends with the proximity-out step.
std::vector<PenStep> uclogicScript(const UclogicModel& m) {
  std::vector<PenStep> all = penScript(m.x_max, m.y_max, m.pressure_max, 0), steps;
  for (PenStep s : all) {
    s.serial = 0;
    s.tool_type = 0;
    s.tilt_x = m.tilt ? std::clamp(s.tilt_x, -60, 60) : 0;
    s.tilt_y = m.tilt ? std::clamp(s.tilt_y, -60, 60) : 0;
    steps.push_back(s);
    if (!s.sense) break;
  }
  // Before the lift (the last two steps: hover, out): draw to the far corner.
  PenStep corner = steps[steps.size() - 3];
  corner.barrel = corner.barrel2 = false;
  corner.x = m.x_max - 7;
  corner.y = m.y_max - 5;
  steps.insert(steps.end() - 2, corner);
  corner.x = m.x_max;
  corner.y = m.y_max;
  steps.insert(steps.end() - 2, corner);
  return steps;
}

std::string describe(const PenSample& s) {
  char b[220];
  std::snprintf(b, sizeof b,
                "prox=%d tool=%d x=%d(%.3fmm) y=%d(%.3fmm) p=%d(%.4f) tilt=%d,%d(%.2f,%.2f deg) "
                "buttons=%#x",
                s.in_proximity, static_cast<int>(s.tool), s.x_raw, s.x_mm, s.y_raw, s.y_mm,
                s.pressure_raw, s.pressure, s.tilt_x_raw, s.tilt_y_raw, s.tilt_x_deg, s.tilt_y_deg,
                s.buttons);
  return b;
}

std::string describeInfo(const PenDeviceInfo& d) {
  char b[200];
  std::snprintf(b, sizeof b, "'%s' x 0..%d @%.1f/mm y 0..%d @%.1f/mm p 0..%d tilt %d..%d @%.4f/deg",
                d.name, d.x_max, d.x_res, d.y_max, d.y_res, d.pressure_max, d.tilt_min, d.tilt_max,
                d.tilt_res);
  return b;
}

bool sameInfo(const PenDeviceInfo& a, const PenDeviceInfo& b) {
  return a.x_max == b.x_max && a.y_max == b.y_max && a.x_res == b.x_res && a.y_res == b.y_res &&
         a.pressure_max == b.pressure_max && a.tilt_min == b.tilt_min && a.tilt_max == b.tilt_max &&
         a.tilt_res == b.tilt_res;
}

// The HID device the kernel made for the model's pen interface: its sysfs directory, or "".
// Its interfaces share the vendor and product ids; the pen's is the one bound to a driver whose
// descriptor is not the device's.
std::string hidSysfsDir(const UclogicModel& m) {
  char prefix[32];
  std::snprintf(prefix, sizeof prefix, "0003:%04X:%04X.", m.vendor, m.product);
  std::string found;
  if (DIR* d = opendir("/sys/bus/hid/devices")) {
    while (dirent* e = readdir(d)) {
      const std::string dir = std::string("/sys/bus/hid/devices/") + e->d_name;
      if (std::string(e->d_name).rfind(prefix, 0) != 0) continue;
      std::ifstream uevent(dir + "/uevent");
      std::string line, phys;
      while (std::getline(uevent, line))
        if (line.rfind("HID_PHYS=", 0) == 0) phys = line;
      // usbhid's phys ends in "/input<interface number>" (usbhid_probe).
      if (phys.size() > 6 &&
          phys.compare(phys.size() - 7, 7, "/input" + std::to_string(m.pen_interface)) == 0)
        found = dir;
    }
    closedir(d);
  }
  return found;
}

std::vector<uint8_t> readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Control requests: strings 0 (language) to 3, the model's vendor strings and each interface's
// Report descriptor; everything else stalls.
GadgetFsDevice::Answer answers(const UclogicModel& m) {
  return [m](uint8_t type, uint8_t request, uint16_t value, uint16_t index,
             uint16_t) -> std::optional<std::vector<uint8_t>> {
    if (request != USB_REQ_GET_DESCRIPTOR) return std::nullopt;
    if (type == (USB_DIR_IN | USB_RECIP_INTERFACE) && value == 0x2200)
      return index < m.descriptors.size() ? std::optional(m.descriptors[index]) : std::nullopt;
    if (type != USB_DIR_IN || (value >> 8) != USB_DT_STRING) return std::nullopt;
    auto text = [](const std::string& ascii) {
      std::vector<uint8_t> b = {static_cast<uint8_t>(2 + 2 * ascii.size()), USB_DT_STRING};
      for (char c : ascii) b.insert(b.end(), {static_cast<uint8_t>(c), 0});
      return b;
    };
    switch (value & 0xFF) {
      case 0:
        return std::vector<uint8_t>{4, USB_DT_STRING, 0x09, 0x04};
      case 1:
        return text(m.manufacturer);
      case 2:
        return text(m.product_name);
      case 3:
        return text(m.serial);
      default:
        return m.vendor_string(value & 0xFF);
    }
  };
}

// What the driver asked of the device, in order, and the checks on it.
void checkControlRequests(const UclogicModel& m, GadgetFsDevice& gadget, Checker& check) {
  const std::vector<ControlRecord> log = gadget.controlLog();
  const std::vector<OutTransfer> out = gadget.outLog();
  std::printf("  %s: control requests the host sent the device (%zu):\n", m.name.c_str(),
              log.size());
  for (const ControlRecord& r : log) std::printf("    %s\n", describe(r).c_str());
  for (const OutTransfer& t : out) {
    std::printf("    interrupt OUT %02x: %zu bytes", t.endpoint, t.data.size());
    for (uint8_t b : t.data) std::printf(" %02x", b);
    std::printf("\n");
  }
  size_t read = 0;
  for (size_t i = 0; i < m.descriptors.size(); ++i)
    for (const ControlRecord& r : log)
      if (r.request_type == (USB_DIR_IN | USB_RECIP_INTERFACE) && r.value == 0x2200 &&
          r.index == i && r.outcome == ControlRecord::Outcome::kAnswered &&
          r.data.size() == m.descriptors[i].size()) {
        ++read;
        break;
      }
  check(read == m.descriptors.size(),
        m.name + ": usbhid read every interface's report descriptor (" + std::to_string(read) +
            " of " + std::to_string(m.descriptors.size()) + ")");
  m.check_requests(log, out, check);
}

// The descriptor hidraw shows is the driver's template filled with our parameters, not the
// device's own.
void checkRewrittenDescriptor(const UclogicModel& m, Checker& check) {
  const std::vector<uint8_t>& original = m.descriptors[m.pen_interface];
  const std::string dir = hidSysfsDir(m);
  const std::vector<uint8_t> shown = readBytes(dir + "/report_descriptor");
  char driver[256] = {};
  const ssize_t n = readlink((dir + "/driver").c_str(), driver, sizeof driver - 1);
  const std::string bound =
      n > 0 ? std::string(driver).substr(std::string(driver).rfind('/') + 1) : "(none)";
  check(bound == "uclogic", m.name + ": the kernel bound its hid-uclogic driver to interface " +
                                std::to_string(m.pen_interface) + " " + dir + " (driver: " + bound +
                                ")");
  auto parsed = hid::parseReportDescriptor(shown.data(), shown.size());
  std::optional<hid::PenLayout> pen;
  if (parsed.descriptor) pen = hid::findPenLayout(*parsed.descriptor).layout;
  const bool ok = shown != original && pen && pen->report_id == m.pen_report_id &&
                  pen->x.logical_max == m.x_max && pen->y.logical_max == m.y_max &&
                  pen->x.bit_size == m.x_bits && pen->pressure.logical_max == m.pressure_max &&
                  pen->tablet_pick.present && pen->report_bytes == m.report_bytes;
  check(ok, m.name + ": hidraw shows the driver's descriptor (" + std::to_string(shown.size()) +
                " bytes, not the device's " + std::to_string(original.size()) + "): pen report " +
                std::to_string(m.pen_report_id) + " of " + std::to_string(m.report_bytes) +
                " bytes, " + std::to_string(m.x_bits) + "-bit X 0.." + std::to_string(m.x_max) +
                ", Y 0.." + std::to_string(m.y_max) + ", pressure 0.." +
                std::to_string(m.pressure_max) + ", the upper button as Tablet Pick");
}

// One step: inject the model's raw report (or nothing, where the driver's timer ends
// proximity), then every source must give exactly one sample, equal to the script's.
int runSteps(const UclogicModel& m, GadgetFsDevice& gadget, const PenDeviceInfo& info,
             std::vector<PenSource*> sources, Checker& check) {
  const std::vector<PenStep> steps = uclogicScript(m);
  PenSample previous{};
  int mismatches = 0, samples = 0;
  for (size_t i = 0; i < steps.size(); ++i) {
    PenSample expected;
    const bool expect = expectedSample(steps[i], info, false, previous, expected);
    std::string error;
    const auto report = m.raw_report(steps[i]);
    if (report && !gadget.send(m.pen_interface, *report, 1000, &error)) {
      check(false, m.name + ": sending step " + std::to_string(i) + ": " + error);
      return mismatches + 1;
    }
    for (PenSource* src : sources) {
      std::vector<PenSample> got;
      const int64_t start = nowNs();
      while (got.empty() && nowNs() - start < 1'000'000'000) src->poll(10, got);
      src->poll(5, got);
      const bool ok = expect && got.size() == 1 && samePenState(got[0], expected);
      if (!ok && mismatches < 8) {
        std::printf("  %s step %zu via %s: expected %s\n", m.name.c_str(), i, src->backendName(),
                    describe(expected).c_str());
        for (const PenSample& g : got)
          std::printf("  %s step %zu via %s:      got %s\n", m.name.c_str(), i, src->backendName(),
                      describe(g).c_str());
      }
      mismatches += !ok;
      samples += static_cast<int>(got.size());
    }
  }
  check(mismatches == 0, m.name + ": " + std::to_string(steps.size()) +
                             " script steps (hover, touch, pressure ramp, " +
                             (m.tilt ? "tilt sweep" : "no tilt axes") +
                             ", both "
                             "buttons, far corner, lift, out) equal on evdev and hidraw, field "
                             "by field (" +
                             std::to_string(samples) + " samples, " + std::to_string(mismatches) +
                             " mismatches)");
  return mismatches;
}

void checkLibusbIdentity(const UclogicModel& m, Checker& check) {
  bool seen = false;
  for (const auto& d : usb::listUsbDevices(m.vendor)) {
    std::printf("  libusb: %04x:%04x bus %d addr %d '%s' '%s' serial '%s' %s\n", d.vendor,
                d.product, d.bus, d.address, d.manufacturer.c_str(), d.product_name.c_str(),
                d.serial.c_str(), d.open_error.c_str());
    seen |= d.product == m.product && d.manufacturer == m.manufacturer &&
            d.product_name == m.product_name && d.serial == m.serial;
  }
  char id[16];
  std::snprintf(id, sizeof id, "%04x:%04x", m.vendor, m.product);
  check(seen, m.name + ": libusb reads the identity " + id + ", '" + m.manufacturer + "' '" +
                  m.product_name + "', serial");
}

GadgetFsConfig gadgetConfig(const UclogicModel& m) {
  GadgetFsConfig config;
  config.vendor = m.vendor;
  config.product = m.product;
  for (size_t i = 0; i < m.descriptors.size(); ++i) {
    GadgetFsInterface f;
    f.report_descriptor_length = static_cast<uint16_t>(m.descriptors[i].size());
    f.interrupt_out = m.magic_out && i == m.pen_interface;
    config.interfaces.push_back(f);
  }
  return config;
}

// The evdev and hidraw checks on the pen the driver made, then the script through both.
void checkPen(const UclogicModel& m, GadgetFsDevice& gadget, EvdevPenSource& evdev,
              Checker& check) {
  checkRewrittenDescriptor(m, check);
  hid::HidapiPenSource hidraw(hidOptions(hid::HidapiBackend::kHidraw, m.vendor));
  if (!check(waitConnected(hidraw, 5000),
             m.name + ": hidapi-hidraw decodes the pen: " + hidraw.statusMessage()))
    return;
  const PenDeviceInfo info = evdev.deviceInfo();
  std::printf("  evdev : %s\n  hidraw: %s\n", describeInfo(info).c_str(),
              describeInfo(hidraw.deviceInfo()).c_str());
  check(std::string(info.name) == m.pen_node, m.name + ": the pen node is named by hid-uclogic ('" +
                                                  info.name + "', expected '" + m.pen_node + "')");
  check(info.x_max == m.x_max && info.y_max == m.y_max && info.pressure_max == m.pressure_max &&
            info.tilt_min == m.tilt_min && info.tilt_max == m.tilt_max,
        m.name + ": evdev's ranges are the parameters we served (x 0.." + std::to_string(m.x_max) +
            ", y 0.." + std::to_string(m.y_max) + ", pressure 0.." +
            std::to_string(m.pressure_max) + ", tilt " + std::to_string(m.tilt_min) + ".." +
            std::to_string(m.tilt_max) + ")");
  check(sameInfo(info, hidraw.deviceInfo()),
        m.name + ": ranges and resolutions on hidraw equal the kernel's absinfo");
  checkLibusbIdentity(m, check);
  runSteps(m, gadget, info, {&evdev, &hidraw}, check);
}

void runModel(const UclogicModel& m, Checker& check) {
  std::string figure = m.name;
  std::replace(figure.begin(), figure.end(), '-', '_');
  const size_t pen_descriptor = m.descriptors.at(m.pen_interface).size();
  if (!check(pen_descriptor > 0, m.name + ": the pen interface's own report descriptor (" +
                                     std::to_string(pen_descriptor) + " bytes)"))
    return;
  GadgetFsDevice gadget;
  std::string error;
  const int64_t t0 = nowNs();
  char id[16];
  std::snprintf(id, sizeof id, "%04x:%04x", m.vendor, m.product);
  if (!check(gadget.start(gadgetConfig(m), answers(m), &error),
             m.name + ": GadgetFS device " + id + " on the dummy UDC " + error))
    return;
  EvdevPenSource evdev({});
  const bool evdev_ok = waitConnected(evdev, 20000);
  std::printf("CB-HIL FIGURE %s_plug_to_evdev_ms %.3f\n", figure.c_str(), (nowNs() - t0) / 1e6);
  check(gadget.waitConfigured(1000), m.name + ": the host configured the device");
  checkControlRequests(m, gadget, check);
  if (check(evdev_ok,
            m.name + ": evdev finds the pen node hid-uclogic made: " + evdev.statusMessage()))
    checkPen(m, gadget, evdev, check);
  gadget.stop();
  std::vector<PenSample> drain;
  const int64_t unplug = nowNs();
  while (evdev.connection() == PenConnection::kConnected && nowNs() - unplug < 3'000'000'000)
    evdev.poll(20, drain);
  check(evdev.connection() != PenConnection::kConnected,
        m.name + ": closing the GadgetFS device unplugs it (evdev: " + evdev.statusMessage() + ")");
  std::printf("CB-HIL FIGURE %s_phase_s %.3f\n", figure.c_str(), (nowNs() - t0) / 1e9);
}

// The same XP-Pen without its interrupt OUT endpoint: the magic bytes cannot be sent, so
// hid-uclogic leaves the pen interface "invalid" and unbound (uclogic_probe_interface fails,
// uclogic_params_init_invalid) and no pen node appears. Shows the endpoint is what the driver
// needs, not decoration.
void runWithoutMagicEndpoint(UclogicModel m, Checker& check) {
  m.magic_out = false;
  GadgetFsDevice gadget;
  std::string error;
  if (!check(gadget.start(gadgetConfig(m), answers(m), &error),
             m.name + " without OUT endpoint: GadgetFS device " + error))
    return;
  gadget.waitConfigured(5000);
  EvdevPenSource evdev({});
  const bool pen = waitConnected(evdev, 3000);
  const std::string dir = hidSysfsDir(m);
  char driver[256] = {};
  const bool bound =
      !dir.empty() && readlink((dir + "/driver").c_str(), driver, sizeof driver - 1) > 0;
  const bool asked = !gadget.controlLog().empty();
  check(asked && !pen && !bound && !dir.empty(),
        m.name + " without its OUT endpoint: the host enumerated it, but interface " +
            std::to_string(m.pen_interface) + " stays unbound and no pen node appears (pen: " +
            (pen ? "yes" : "no") + ", driver: " + (bound ? driver : "none") + ")");
  gadget.stop();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
}

}  // namespace

int runUclogicPhase(const std::string& fixtures) {
  Checker check;
  for (const UclogicModel& m : {huionV2Model(fixtures), ugeeV2Model(), ugeeV1Model()})
    runModel(m, check);
  runWithoutMagicEndpoint(ugeeV2Model(), check);
  return check.failures;
}

}  // namespace cb::hil
