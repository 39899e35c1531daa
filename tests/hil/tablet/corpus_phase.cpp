#include "tests/hil/tablet/corpus_phase.h"

#include "tests/hil/tablet/hil_devices.h"

#include <linux/input.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <vector>

#include "drivers/core/clock.h"
#include "drivers/evdev/evdev_pen_source.h"
#include "drivers/hid/hidapi_pen_source.h"
#include "tests/hil/tablet/pen_corpus.h"
#include "tests/hil/tablet/uhid_device.h"

namespace cb::hil {
namespace {

int64_t nowNs() {
  return MonotonicClock().nowNs();
}

struct Checker {
  int failures = 0;
  bool operator()(bool ok, const std::string& what) {
    std::printf("CB-HIL CHECK %s %s\n", ok ? "ok" : "FAIL", what.c_str());
    std::fflush(stdout);
    if (!ok) ++failures;
    return ok;
  }
};

std::string describe(const PenSample& s) {
  char b[200];
  std::snprintf(b, sizeof b, "prox=%d tool=%d x=%d y=%d p=%d tilt=%d,%d buttons=%#x serial=%#llx",
                s.in_proximity, static_cast<int>(s.tool), s.x_raw, s.y_raw, s.pressure_raw,
                s.tilt_x_raw, s.tilt_y_raw, s.buttons,
                static_cast<unsigned long long>(s.tool_serial));
  return b;
}

bool waitConnected(PenSource& src, int timeout_ms) {
  const int64_t start = nowNs();
  std::vector<PenSample> ignored;
  while (src.connection() != PenConnection::kConnected) {
    if (nowNs() - start > int64_t{timeout_ms} * 1000000) return false;
    src.poll(20, ignored);
  }
  return true;
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
  // Without an In Range usage hid-input maps no BTN_TOOL_PEN: the node is no pen for evdev.
  const bool kernel_pen = dev.ranges.count("inrange") == 1;
  EvdevPenSource evdev({});
  hid::HidapiPenSource hidraw(hidOptions(hid::HidapiBackend::kHidraw, dev.vendor));
  const bool evdev_ok = kernel_pen && waitConnected(evdev, 5000);
  if (kernel_pen) check(evdev_ok, label + ": evdev finds the pen node: " + evdev.statusMessage());
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
