#include "tests/hil/tablet/uclogic_phase.h"

#include <dirent.h>
#include <linux/usb/ch9.h>
#include <unistd.h>

#include <algorithm>
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

namespace cb::hil {
namespace {

// The identity: Huion's vendor id and the product id hid-uclogic lists as
// USB_DEVICE_ID_HUION_TABLET (drivers/hid/hid-ids.h), shared by the H610 Pro, Gaomon S56K and
// others. uclogic_params_init sends this id to uclogic_params_huion_init.
constexpr uint16_t kVendor = 0x256C, kProduct = 0x006E;
const char* const kManufacturer = "HUION";
// The HID name becomes "HUION PenTablet", the name the H610 Pro's descriptor dump carries.
const char* const kProductName = "PenTablet";
const char* const kSerial = "CBHIL0003";
// String 201: the firmware name uclogic_params_huion_init reads with usb_string(); only
// "HUION_T153_160607" (a transition firmware) keeps it from probing the v2 parameters. This
// one says what it is.
const char* const kFirmware = "CBHIL_EMULATED_V2";

// The v2 parameters (string 200, read by uclogic_params_pen_init_v2 with wLength 32 and
// langid 0x0409; at least 18 bytes, not all UTF-16 text): X and Y logical maxima (24 bit at
// bytes 2 and 5), pressure maximum (16 bit at 8), resolution in lines per inch (16 bit at 10).
// Both maxima above 65535, so every far position needs the high bytes the driver moves
// (fragmented_hires); 5080 lpi, as in the HS610 block hid-uclogic quotes
// (uclogic_params_huion_init, touch_ring_model_params_buf). The bytes after 12 (unknown to the
// driver) are zero.
constexpr int32_t kXMax = 120000, kYMax = 75000, kPressureMax = 8191, kLpi = 5080;
constexpr uint8_t kV2PenReportId = 8;  // UCLOGIC_RDESC_V2_PEN_ID (hid-uclogic-rdesc.h)

std::vector<uint8_t> parameterBlock() {
  std::vector<uint8_t> b(19, 0);
  b[0] = 19;
  b[1] = USB_DT_STRING;
  auto le = [&](size_t at, int32_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) b[at + i] = (v >> (8 * i)) & 0xFF;
  };
  le(2, kXMax, 3);
  le(5, kYMax, 3);
  le(8, kPressureMax, 2);
  le(10, kLpi, 2);
  return b;
}

std::vector<uint8_t> stringDescriptor(const std::string& ascii) {
  std::vector<uint8_t> b = {static_cast<uint8_t>(2 + 2 * ascii.size()), USB_DT_STRING};
  for (char c : ascii) b.insert(b.end(), {static_cast<uint8_t>(c), 0});
  return b;
}

// The raw vendor pen report a v2 tablet sends on interface 0, in the byte order
// uclogic_raw_event_pen (hid-uclogic-core.c) undoes: ID 8; state bits (tip, barrel, upper
// button; bit 7 set as the tablet's firmware does, bit 6 "in range" left clear because the v2
// parameters make the driver set it itself: UCLOGIC_PARAMS_PEN_INRANGE_NONE); X and Y low 16
// bits; pressure; X and Y high bytes (fragmented_hires); tilt X; tilt Y the other way round
// (tilt_y_flipped: the driver negates it).
std::vector<uint8_t> rawV2Report(const PenStep& s) {
  std::vector<uint8_t> r(12, 0);
  r[0] = kV2PenReportId;
  r[1] = 0x80 | (s.tip ? 0x01 : 0) | (s.barrel ? 0x02 : 0) | (s.barrel2 ? 0x04 : 0);
  r[2] = s.x & 0xFF;
  r[3] = (s.x >> 8) & 0xFF;
  r[4] = s.y & 0xFF;
  r[5] = (s.y >> 8) & 0xFF;
  r[6] = s.pressure & 0xFF;
  r[7] = (s.pressure >> 8) & 0xFF;
  r[8] = (s.x >> 16) & 0xFF;
  r[9] = (s.y >> 16) & 0xFF;
  r[10] = static_cast<uint8_t>(static_cast<int8_t>(s.tilt_x));
  r[11] = static_cast<uint8_t>(static_cast<int8_t>(-s.tilt_y));
  return r;
}

// The pen part of the common script (the v2 pen has no eraser end and no distance), tilts
// within the template's -60..60, no serial or tool id (the pen reports none), and a stroke to
// the far corner where both axes need their high byte. Ends with the proximity-out step.
std::vector<PenStep> uclogicScript() {
  std::vector<PenStep> all = penScript(kXMax, kYMax, kPressureMax, 0), steps;
  for (PenStep s : all) {
    s.serial = 0;
    s.tool_type = 0;
    s.tilt_x = std::clamp(s.tilt_x, -60, 60);
    s.tilt_y = std::clamp(s.tilt_y, -60, 60);
    steps.push_back(s);
    if (!s.sense) break;
  }
  // Before the lift (the last two steps: hover, out): draw to the far corner.
  PenStep corner = steps[steps.size() - 3];
  corner.barrel = corner.barrel2 = false;
  corner.x = kXMax - 7;
  corner.y = kYMax - 5;
  steps.insert(steps.end() - 2, corner);
  corner.x = kXMax;
  corner.y = kYMax;
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

// The HID device the kernel made for our gadget: its sysfs directory, or "".
std::string hidSysfsDir() {
  char prefix[32];
  std::snprintf(prefix, sizeof prefix, "0003:%04X:%04X.", kVendor, kProduct);
  std::string found;
  if (DIR* d = opendir("/sys/bus/hid/devices")) {
    while (dirent* e = readdir(d))
      if (std::string(e->d_name).rfind(prefix, 0) == 0)
        found = std::string("/sys/bus/hid/devices/") + e->d_name;
    closedir(d);
  }
  return found;
}

std::vector<uint8_t> readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Control requests: strings 0 (language), 1-3, 200 (v2 parameters), 201 (firmware name) and the
// interface's Report descriptor; everything else (string 100 included: the v1 parameters a v2
// tablet is not asked for) stalls.
GadgetFsDevice::Answer huionAnswers(const std::vector<uint8_t>& report_descriptor) {
  return [report_descriptor](uint8_t type, uint8_t request, uint16_t value, uint16_t index,
                             uint16_t) -> std::optional<std::vector<uint8_t>> {
    if (request != USB_REQ_GET_DESCRIPTOR) return std::nullopt;
    if (type == (USB_DIR_IN | USB_RECIP_INTERFACE) && value == 0x2200 && index == 0)
      return report_descriptor;
    if (type != USB_DIR_IN || (value >> 8) != USB_DT_STRING) return std::nullopt;
    switch (value & 0xFF) {
      case 0:
        return std::vector<uint8_t>{4, USB_DT_STRING, 0x09, 0x04};
      case 1:
        return stringDescriptor(kManufacturer);
      case 2:
        return stringDescriptor(kProductName);
      case 3:
        return stringDescriptor(kSerial);
      case 200:
        return parameterBlock();
      case 201:
        return stringDescriptor(kFirmware);
      default:
        return std::nullopt;
    }
  };
}

// What the driver asked of the device, in order, and the checks on it.
void checkControlRequests(GadgetFsDevice& gadget, size_t descriptor_size, Checker& check) {
  const std::vector<ControlRecord> log = gadget.controlLog();
  std::printf("  uclogic: control requests the host sent the device (%zu):\n", log.size());
  for (const ControlRecord& r : log) std::printf("    %s\n", describe(r).c_str());
  auto find = [&](uint8_t type, uint16_t value) -> const ControlRecord* {
    for (const ControlRecord& r : log)
      if (r.request_type == type && r.request == USB_REQ_GET_DESCRIPTOR && r.value == value)
        return &r;
    return nullptr;
  };
  const ControlRecord* v2 = find(USB_DIR_IN, 0x0300 | 200);
  const ControlRecord* fw = find(USB_DIR_IN, 0x0300 | 201);
  const ControlRecord* v1 = find(USB_DIR_IN, 0x0300 | 100);
  const ControlRecord* rdesc = find(USB_DIR_IN | USB_RECIP_INTERFACE, 0x2200);
  check(rdesc && rdesc->outcome == ControlRecord::Outcome::kAnswered &&
            rdesc->data.size() == descriptor_size,
        "uclogic: usbhid read the interface's report descriptor (" +
            std::to_string(descriptor_size) + " bytes answered)");
  check(fw && fw->outcome == ControlRecord::Outcome::kAnswered,
        "uclogic: hid-uclogic read the firmware name (string 201)");
  check(v2 && v2->index == 0x0409 && v2->length == 32 &&
            v2->outcome == ControlRecord::Outcome::kAnswered && v2->data.size() == 19 &&
            (!fw || fw < v2),
        "uclogic: hid-uclogic then read the v2 pen parameters (string 200, langid 0x0409, "
        "wLength 32; 19 bytes answered)");
  check(!v1, "uclogic: with v2 parameters found it did not ask for the v1 ones (string 100)");
}

// The descriptor hidraw shows is the driver's v2 template filled with our parameters, not the
// device's own.
void checkRewrittenDescriptor(const std::vector<uint8_t>& original, Checker& check) {
  const std::string dir = hidSysfsDir();
  const std::vector<uint8_t> shown = readBytes(dir + "/report_descriptor");
  char driver[256] = {};
  const ssize_t n = readlink((dir + "/driver").c_str(), driver, sizeof driver - 1);
  const std::string bound =
      n > 0 ? std::string(driver).substr(std::string(driver).rfind('/') + 1) : "(none)";
  check(bound == "uclogic",
        "uclogic: the kernel bound its hid-uclogic driver to " + dir + " (driver: " + bound + ")");
  auto parsed = hid::parseReportDescriptor(shown.data(), shown.size());
  std::optional<hid::PenLayout> pen;
  if (parsed.descriptor) pen = hid::findPenLayout(*parsed.descriptor).layout;
  const bool ok = shown != original && pen && pen->report_id == kV2PenReportId &&
                  pen->x.logical_max == kXMax && pen->y.logical_max == kYMax &&
                  pen->x.bit_size == 24 && pen->pressure.logical_max == kPressureMax &&
                  pen->tablet_pick.present && pen->report_bytes == 12;
  check(ok, "uclogic: hidraw shows the driver's descriptor (" + std::to_string(shown.size()) +
                " bytes, not the device's " + std::to_string(original.size()) +
                "): pen report 8 of 12 bytes, 24-bit X 0.." + std::to_string(kXMax) + ", Y 0.." +
                std::to_string(kYMax) + ", pressure 0.." + std::to_string(kPressureMax) +
                ", the upper button as Tablet Pick");
}

// One step: inject (or, for proximity out, send nothing: the driver's 100 ms timer ends it),
// then every source must give exactly one sample, equal to the script's.
int runSteps(GadgetFsDevice& gadget, const PenDeviceInfo& info, std::vector<PenSource*> sources,
             Checker& check) {
  const std::vector<PenStep> steps = uclogicScript();
  PenSample previous{};
  int mismatches = 0, samples = 0;
  for (size_t i = 0; i < steps.size(); ++i) {
    PenSample expected;
    const bool expect = expectedSample(steps[i], info, false, previous, expected);
    std::string error;
    if (steps[i].sense && !gadget.send(rawV2Report(steps[i]), 1000, &error)) {
      check(false, "uclogic: sending step " + std::to_string(i) + ": " + error);
      return mismatches + 1;
    }
    for (PenSource* src : sources) {
      std::vector<PenSample> got;
      const int64_t start = nowNs();
      while (got.empty() && nowNs() - start < 1'000'000'000) src->poll(10, got);
      src->poll(5, got);
      const bool ok = expect && got.size() == 1 && samePenState(got[0], expected);
      if (!ok && mismatches < 8) {
        std::printf("  uclogic step %zu via %s: expected %s\n", i, src->backendName(),
                    describe(expected).c_str());
        for (const PenSample& g : got)
          std::printf("  uclogic step %zu via %s:      got %s\n", i, src->backendName(),
                      describe(g).c_str());
      }
      mismatches += !ok;
      samples += static_cast<int>(got.size());
    }
  }
  check(mismatches == 0, "uclogic: " + std::to_string(steps.size()) +
                             " script steps (hover, touch, pressure ramp, tilt sweep, both "
                             "buttons, far corner, lift, out) equal on evdev and hidraw, field "
                             "by field (" +
                             std::to_string(samples) + " samples, " + std::to_string(mismatches) +
                             " mismatches)");
  return mismatches;
}

void checkLibusbIdentity(Checker& check) {
  bool seen = false;
  for (const auto& d : usb::listUsbDevices(kVendor)) {
    std::printf("  libusb: %04x:%04x bus %d addr %d '%s' '%s' serial '%s' %s\n", d.vendor,
                d.product, d.bus, d.address, d.manufacturer.c_str(), d.product_name.c_str(),
                d.serial.c_str(), d.open_error.c_str());
    seen |= d.product == kProduct && d.manufacturer == kManufacturer &&
            d.product_name == kProductName && d.serial == kSerial;
  }
  check(seen, "uclogic: libusb reads the identity 256c:006e, 'HUION' 'PenTablet', serial");
}

}  // namespace

int runUclogicPhase(const std::string& fixtures) {
  Checker check;
  const std::vector<uint8_t> original = readBytes(fixtures + "/huion-h610-pro_256c_006e.rdesc");
  if (!check(original.size() == 179, "uclogic: the H610 Pro's interface-0 descriptor (179 bytes)"))
    return check.failures;
  GadgetFsDevice gadget;
  GadgetFsConfig config;
  config.vendor = kVendor;
  config.product = kProduct;
  config.report_descriptor_length = static_cast<uint16_t>(original.size());
  std::string error;
  const int64_t t0 = nowNs();
  if (!check(gadget.start(config, huionAnswers(original), &error),
             "uclogic: GadgetFS device 256c:006e on the dummy UDC " + error))
    return check.failures;
  EvdevPenSource evdev({});
  const bool evdev_ok = waitConnected(evdev, 20000);
  std::printf("CB-HIL FIGURE uclogic_plug_to_evdev_ms %.3f\n", (nowNs() - t0) / 1e6);
  check(gadget.waitConfigured(1000), "uclogic: the host configured the device");
  checkControlRequests(gadget, original.size(), check);
  if (!check(evdev_ok,
             "uclogic: evdev finds the pen node hid-uclogic made: " + evdev.statusMessage()))
    return check.failures;
  checkRewrittenDescriptor(original, check);
  hid::HidapiPenSource hidraw(hidOptions(hid::HidapiBackend::kHidraw, kVendor));
  if (!check(waitConnected(hidraw, 5000),
             "uclogic: hidapi-hidraw decodes the pen: " + hidraw.statusMessage()))
    return check.failures;
  const PenDeviceInfo info = evdev.deviceInfo();
  std::printf("  evdev : %s\n  hidraw: %s\n", describeInfo(info).c_str(),
              describeInfo(hidraw.deviceInfo()).c_str());
  check(std::string(info.name) == "HUION PenTablet Pen",
        std::string("uclogic: the pen node is named by hid-uclogic ('") + info.name + "')");
  check(info.x_max == kXMax && info.y_max == kYMax && info.pressure_max == kPressureMax &&
            info.tilt_min == -60 && info.tilt_max == 60,
        "uclogic: evdev's ranges are the parameters we served (x 0.." + std::to_string(kXMax) +
            ", y 0.." + std::to_string(kYMax) + ", pressure 0.." + std::to_string(kPressureMax) +
            ", tilt -60..60)");
  check(sameInfo(info, hidraw.deviceInfo()),
        "uclogic: ranges and resolutions on hidraw equal the kernel's absinfo");
  checkLibusbIdentity(check);
  runSteps(gadget, info, {&evdev, &hidraw}, check);
  gadget.stop();
  std::vector<PenSample> drain;
  const int64_t unplug = nowNs();
  while (evdev.connection() == PenConnection::kConnected && nowNs() - unplug < 3'000'000'000)
    evdev.poll(20, drain);
  check(evdev.connection() != PenConnection::kConnected,
        "uclogic: closing the GadgetFS device unplugs it (evdev: " + evdev.statusMessage() + ")");
  hidraw.poll(50, drain);
  std::printf("CB-HIL FIGURE uclogic_phase_s %.3f\n", (nowNs() - t0) / 1e9);
  return check.failures;
}

}  // namespace cb::hil
