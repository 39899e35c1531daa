#include "tests/hil/tablet/corpus_phase.h"

#include "tests/hil/tablet/hil_checks.h"
#include "tests/hil/tablet/hil_devices.h"

#include <fcntl.h>
#include <linux/input.h>
#include <sys/utsname.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "drivers/core/clock.h"
#include "drivers/evdev/evdev_pen_source.h"
#include "drivers/hid/hid_report_descriptor.h"
#include "drivers/hid/hidapi_pen_source.h"
#include "tests/hil/tablet/pen_corpus.h"
#include "tests/hil/tablet/uhid_device.h"

namespace cb::hil {
namespace {

std::string describe(const PenSample& s) {
  char b[200];
  std::snprintf(b, sizeof b, "prox=%d tool=%d x=%d y=%d p=%d tilt=%d,%d buttons=%#x serial=%#llx",
                s.in_proximity, static_cast<int>(s.tool), s.x_raw, s.y_raw, s.pressure_raw,
                s.tilt_x_raw, s.tilt_y_raw, s.buttons,
                static_cast<unsigned long long>(s.tool_serial));
  return b;
}

// Polls until the source's state satisfies the step (or `timeout_ms`), then drains briefly;
// the state is the last sample received (evdev sends nothing when nothing changed). Returns
// whether a proximity-out sample came before a final in-proximity one (a tool released and
// taken again within one report).
bool settle(PenSource& src, const CorpusStep& st, PenSample& state, int timeout_ms) {
  std::vector<PenSample> got, all;
  const int64_t deadline = nowNs() + int64_t{timeout_ms} * 1000000;
  while (nowNs() < deadline) {
    got.clear();
    src.poll(5, got);
    all.insert(all.end(), got.begin(), got.end());
    if (!got.empty()) state = got.back();
    if (!all.empty() && corpusMismatch(st, state).empty()) break;
  }
  got.clear();
  src.poll(2, got);
  all.insert(all.end(), got.begin(), got.end());
  if (!got.empty()) state = got.back();
  bool out_then_in = false;
  for (size_t i = 0; i + 1 < all.size(); ++i)
    out_then_in |= !all[i].in_proximity && all.back().in_proximity;
  return out_then_in;
}

// The kernel's own account of the input nodes made for the device named `name`
// (/proc/bus/input/devices: name, handlers, key and abs bits), for a check that fails.
std::string kernelInputNodes(const std::string& name) {
  std::ifstream in("/proc/bus/input/devices");
  std::string line, block, found;
  const auto flush = [&] {
    if (block.find(name) != std::string::npos) found += block;
    block.clear();
  };
  while (std::getline(in, line)) {
    if (line.empty()) {
      flush();
      continue;
    }
    if (line.rfind("N:", 0) == 0 || line.rfind("H:", 0) == 0 || line.rfind("B: KEY", 0) == 0 ||
        line.rfind("B: ABS", 0) == 0 || line.rfind("B: PROP", 0) == 0)
      block += " [" + line + "]";
  }
  flush();
  if (!found.empty()) return found;
  // No node: what the kernel logged about HID devices (bound driver, hid-input's refusal).
  std::string log;
  if (FILE* kmsg = std::fopen("/dev/kmsg", "re")) {
    const int fd = fileno(kmsg);
    ::fcntl(fd, F_SETFL, O_NONBLOCK);
    char record[2048];
    ssize_t n;
    while ((n = ::read(fd, record, sizeof record - 1)) > 0) {
      record[n] = 0;
      const std::string text(record);
      if (text.find("hid") != std::string::npos || text.find("input") != std::string::npos)
        log += " [" + text.substr(text.find(';') + 1, text.find('\n') - text.find(';') - 1) + "]";
    }
    std::fclose(kmsg);
  }
  return " (the kernel made no input node for it; its HID log:" + log + ")";
}

// Whether hid-input makes input nodes for the descriptor on the running kernel: only for an
// application collection its IS_INPUT_APPLICATION names (include/linux/hid.h). Generic Desktop
// Pointer..Multi-axis and Digitizer Pen..Whiteboard always; the Digitizer application (0x0D 0x01,
// the usage hid-uclogic's pen templates switched to) only from Linux 6.2, where the range was
// widened to start at HID_DG_DIGITIZER. Before that such a pen has hidraw but no input node.
bool kernelMakesInputNode(const std::vector<uint8_t>& desc, std::string* why) {
  const hid::ParseResult parsed = hid::parseReportDescriptor(desc.data(), desc.size());
  if (!parsed.descriptor) return false;
  utsname u{};
  int major = 0, minor = 0;
  if (::uname(&u) == 0) std::sscanf(u.release, "%d.%d", &major, &minor);
  const bool digitizer_counts = major > 6 || (major == 6 && minor >= 2);
  for (const hid::Field& f : parsed.descriptor->fields) {
    const uint32_t a = f.application;
    if ((a >= 0x00010000 && a <= 0x00010008) || (a >= 0x000d0002 && a <= 0x000d0006) ||
        (a == 0x000d0001 && digitizer_counts))
      return true;
  }
  *why = std::string("its application is no input application for hid-input on Linux ") +
         u.release + " (the Digitizer application counts from 6.2)";
  return false;
}

bool sameFields(const PenSample& a, const PenSample& b) {
  if (!a.in_proximity && !b.in_proximity) return true;
  return a.in_proximity == b.in_proximity && a.tool == b.tool && a.buttons == b.buttons &&
         a.x_raw == b.x_raw && a.y_raw == b.y_raw && a.pressure_raw == b.pressure_raw &&
         a.tilt_x_raw == b.tilt_x_raw && a.tilt_y_raw == b.tilt_y_raw && a.x_mm == b.x_mm &&
         a.y_mm == b.y_mm && a.pressure == b.pressure && a.tilt_x_deg == b.tilt_x_deg;
}

bool sameInfo(const PenDeviceInfo& a, const PenDeviceInfo& b) {
  return a.x_max == b.x_max && a.y_max == b.y_max && a.x_res == b.x_res && a.y_res == b.y_res &&
         a.pressure_max == b.pressure_max && a.tilt_min == b.tilt_min && a.tilt_max == b.tilt_max &&
         a.tilt_res == b.tilt_res;
}

void runDevice(const std::string& fixtures, const CorpusDevice& dev, Checker& check) {
  std::ifstream in(fixtures + "/" + dev.file, std::ios::binary);
  const std::vector<uint8_t> desc{std::istreambuf_iterator<char>(in),
                                  std::istreambuf_iterator<char>()};
  const std::string label = "corpus " + dev.file;
  UhidDevice u;
  std::string error;
  if (!check(u.create("cloudbrush corpus " + dev.file.substr(0, dev.file.find('.')), desc,
                      dev.i2c() ? BUS_I2C : BUS_USB, dev.vendor, dev.product, &error),
             label + ": UHID_CREATE2 " + error))
    return;
  // Without an In Range usage hid-input maps no BTN_TOOL_PEN: the node is no pen for evdev;
  // without an input application it makes no node at all.
  std::string no_node;
  const bool kernel_pen = dev.ranges.count("inrange") == 1 && kernelMakesInputNode(desc, &no_node);
  EvdevPenSource evdev({});
  hid::HidapiPenSource hidraw(hidOptions(hid::HidapiBackend::kHidraw, dev.vendor));
  const bool evdev_ok = kernel_pen && waitConnected(evdev, 5000);
  if (!no_node.empty()) {
    EvdevPenSource absent({});
    check(!waitConnected(absent, 1000),
          label + ": no pen node, as the kernel's rule says (" + no_node + ")");
  }
  if (kernel_pen)
    check(evdev_ok, label + ": evdev finds the pen node: " + evdev.statusMessage() +
                        (evdev_ok ? "" : kernelInputNodes(dev.file.substr(0, dev.file.find('.')))));
  if (!check(waitConnected(hidraw, 5000),
             label + ": hidraw decodes the pen: " + hidraw.statusMessage()))
    return;
  if (evdev_ok)
    check(sameInfo(evdev.deviceInfo(), hidraw.deviceInfo()),
          label + ": ranges and resolutions from the descriptor equal the kernel's absinfo (x " +
              std::to_string(evdev.deviceInfo().x_res) + "/mm vs " +
              std::to_string(hidraw.deviceInfo().x_res) + "/mm, tilt " +
              std::to_string(evdev.deviceInfo().tilt_res) + " vs " +
              std::to_string(hidraw.deviceInfo().tilt_res) + ")");
  PenSample ev{}, hr{};
  int ev_bad = 0, hr_bad = 0, differ = 0, printed = 0, flips = 0;
  for (const CorpusStep& st : dev.steps) {
    if (!u.input(st.report)) {
      check(false, label + ": injecting " + st.name);
      return;
    }
    const bool hr_flip = settle(hidraw, st, hr, corpusMismatch(st, hr).empty() ? 30 : 500);
    const std::string hr_why = corpusMismatch(st, hr);
    std::string ev_why, diff;
    if (evdev_ok) {
      const bool ev_flip = settle(evdev, st, ev, corpusMismatch(st, ev).empty() ? 30 : 500);
      ev_why = corpusMismatch(st, ev);
      if (st.expect != "any" && !sameFields(ev, hr)) diff = "evdev and hidraw differ";
      if (ev_flip != hr_flip)
        diff += std::string(" proximity-out frame within the report on ") +
                (ev_flip ? "evdev only" : "hidraw only");
      flips += ev_flip;
    }
    if (!hr_why.empty() || !ev_why.empty() || !diff.empty()) {
      if (printed++ < 6) {
        std::printf("  %s line %d %s (%s):\n", dev.file.c_str(), st.line, st.name.c_str(),
                    st.expect.c_str());
        if (evdev_ok) std::printf("    evdev : %s %s\n", describe(ev).c_str(), ev_why.c_str());
        std::printf("    hidraw: %s %s\n", describe(hr).c_str(), hr_why.c_str());
      }
      ev_bad += !ev_why.empty();
      hr_bad += !hr_why.empty();
      differ += !diff.empty();
    }
  }
  const std::string n = std::to_string(dev.steps.size());
  if (evdev_ok) {
    check(ev_bad == 0, label + ": evdev follows the script (" + std::to_string(ev_bad) + " of " +
                           n + " steps off)");
    check(differ == 0, label + ": evdev and hidraw agree field by field (" +
                           std::to_string(differ) + " of " + n + " steps differ; " +
                           std::to_string(flips) + " tool release(s) within a report on both)");
  }
  check(hr_bad == 0, label + ": hidraw follows the script (" + std::to_string(hr_bad) + " of " + n +
                         " steps off)");
  u.destroy();
  std::vector<PenSample> drain;
  evdev.poll(50, drain);
  hidraw.poll(50, drain);
}

}  // namespace

int runCorpusPhase(const std::string& fixtures) {
  Checker check;
  std::string error;
  const auto devices = readPenCorpus(fixtures + "/pen_corpus_reports.txt", &error);
  if (!check(error.empty() && !devices.empty(), "corpus: script read " + error))
    return check.failures;
  const int64_t start = nowNs();
  for (const CorpusDevice& dev : devices) runDevice(fixtures, dev, check);
  std::printf("CB-HIL FIGURE corpus_phase_s %.3f\n", (nowNs() - start) / 1e9);
  return check.failures;
}

}  // namespace cb::hil
