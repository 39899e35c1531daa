// Runs INSIDE the qemu guest of kms_kiosk_test, beside `cloudbrush kiosk`: a Wacom tablet
// (the PTH-660 fixture descriptor) plugged in and out through /dev/uhid, the kernel's own wacom
// driver binding it each time. Per cycle: UHID_CREATE2 (its CLOCK_MONOTONIC time printed), the
// pen hovering until the kiosk's log (KIOSK_LOG) says that the first sample after the connection
// reached its screen (app/shell/kiosk/kiosk_screen.cpp) — at most 60 s, so a frame loop slowed by
// emulation still sees every plug — then a short stroke, proximity out, UHID_DESTROY; then a
// wait until the kiosk noticed the unplug, and a pause. The host pairs the creation times with
// the kiosk's log lines.
//
//   kiosk_pen_hotplug DESCRIPTOR.rdesc KIOSK_LOG LABEL CYCLES PAUSE_MS
//
// Prints "KIOSK-PEN created LABEL I T_S", "KIOSK-PEN destroyed LABEL I" and "KIOSK-PEN done".
#include <linux/input.h>
#include <poll.h>
#include <sys/inotify.h>
#include <unistd.h>

#include <atomic>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "drivers/core/clock.h"
#include "drivers/hid/hid_pen_layout.h"
#include "drivers/hid/hid_report_descriptor.h"
#include "drivers/hid/pen_report_encoder.h"
#include "tests/hil/tablet/uhid_device.h"

namespace {

using namespace cb;

// How many lines of the kiosk's log hold `text`.
long countInLog(const std::string& kiosk_log, const char* text) {
  std::ifstream log(kiosk_log);
  long n = 0;
  for (std::string line; std::getline(log, line);) n += line.find(text) != std::string::npos;
  return n;
}

// How many times the kiosk has said a (re)connected pen's first sample reached its screen.
long samplesSeen(const std::string& kiosk_log) {
  return countInLog(kiosk_log, "first sample since it connected");
}

// The kiosk says "the pen was unplugged" (from a visit) or "pen searching" (any screen).
long unplugsSeen(const std::string& kiosk_log) {
  return countInLog(kiosk_log, "cloudbrush: pen searching");
}

void sleepMs(int ms) {
  std::this_thread::sleep_for(std::chrono::milliseconds(ms));
}

// Prints when each event node appears in /dev/input (inotify, as the kiosk's evdev backend
// watches) as "KIOSK-PEN node LABEL I NAME T_S", while `watching`.
void watchNodes(const std::string& label, const std::atomic<int>& cycle,
                const std::atomic<bool>& watching) {
  const int fd = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
  if (fd < 0 || inotify_add_watch(fd, "/dev/input", IN_CREATE) < 0) return;
  while (watching) {
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, 50) <= 0) continue;
    const int64_t t = MonotonicClock().nowNs();
    alignas(inotify_event) char buf[4096];
    const ssize_t n = read(fd, buf, sizeof buf);
    for (ssize_t at = 0; at < n;) {
      const auto* e = reinterpret_cast<const inotify_event*>(buf + at);
      if (e->len > 0 && std::string(e->name).rfind("event", 0) == 0)
        std::printf("KIOSK-PEN node %s %d %s %.6f\n", label.c_str(), cycle.load(), e->name,
                    double(t) / 1e9);
      at += ssize_t(sizeof(inotify_event) + e->len);
    }
    std::fflush(stdout);
  }
  close(fd);
}

// What one plug cycle needs: the pen's layout, the kiosk's log, the phase's label.
struct Plugger {
  const hid::PenLayout& layout;
  std::vector<uint8_t> desc;
  std::string kiosk_log, label;
};

// Hovering near the middle (a report every 10 ms, at most 60 s) until the kiosk has the pen;
// prints when the kernel's driver started the device (UHID_START) as "KIOSK-PEN started".
void hoverUntilSeen(const Plugger& g, int i, hil::UhidDevice& dev, hid::PenReportState& s) {
  bool start_said = false;
  const long seen_before = samplesSeen(g.kiosk_log);
  const int32_t xm = g.layout.x.logical_max, ym = g.layout.y.logical_max;
  bool seen = false;
  for (int k = 0; k < 6000 && !seen; ++k) {
    s.x = xm / 2 + (k % 20) * xm / 400;
    s.y = ym / 2;
    dev.input(hid::encodePenReport(g.layout, s));
    sleepMs(10);
    if (!start_said && dev.started()) {
      start_said = true;
      std::printf("KIOSK-PEN started %s %d %.6f\n", g.label.c_str(), i,
                  double(MonotonicClock().nowNs()) / 1e9);
      std::fflush(stdout);
    }
    if (k % 10 == 9) seen = samplesSeen(g.kiosk_log) > seen_before;
  }
  if (!seen) std::printf("KIOSK-PEN unseen %s %d\n", g.label.c_str(), i);
}

// A 0.5 s stroke, then the tip up and proximity out.
void strokeAndLeave(const Plugger& g, hil::UhidDevice& dev, hid::PenReportState& s) {
  const int32_t xm = g.layout.x.logical_max, ym = g.layout.y.logical_max;
  s.tip = true;
  s.distance = 0;
  for (int k = 0; k < 50; ++k) {
    const double t = k / 49.0;
    s.x = int32_t(xm * (0.35 + 0.3 * t));
    s.y = int32_t(ym * (0.5 + 0.05 * std::sin(6.28 * t)));
    s.pressure = int32_t(g.layout.pressure.logical_max * (0.3 + 0.5 * std::sin(3.14 * t)));
    dev.input(hid::encodePenReport(g.layout, s));
    sleepMs(10);
  }
  s.tip = false;
  s.pressure = 0;
  s.in_range = s.sense = false;
  dev.input(hid::encodePenReport(g.layout, s));
}

// Plug cycle `i`: created (its time printed), hovered until seen, a stroke, destroyed; then
// until the kiosk noticed, and the pause. False when the device cannot be made.
bool plugCycle(const Plugger& g, int i, int pause_ms, std::atomic<int>& cycle) {
  hil::UhidDevice dev;
  std::string error;
  const int64_t created = MonotonicClock().nowNs();
  if (!dev.create("Wacom Intuos Pro M", g.desc, BUS_USB, 0x056A, 0x0357, &error)) {
    std::printf("KIOSK-PEN FAIL create %s %d: %s\n", g.label.c_str(), i, error.c_str());
    return false;
  }
  cycle = i;
  std::printf("KIOSK-PEN created %s %d %.6f\n", g.label.c_str(), i, double(created) / 1e9);
  std::fflush(stdout);
  hid::PenReportState s;
  s.tool_type = 0x802;
  s.serial = 0x1234;
  s.distance = g.layout.distance.logical_max / 4;
  hoverUntilSeen(g, i, dev, s);
  strokeAndLeave(g, dev, s);
  sleepMs(100);
  const long unplugs_before = unplugsSeen(g.kiosk_log);
  dev.destroy();
  std::printf("KIOSK-PEN destroyed %s %d\n", g.label.c_str(), i);
  std::fflush(stdout);
  // Until the kiosk noticed (a loop slowed by emulation could otherwise miss a quick replug
  // altogether: the pen would look connected throughout), then the pause.
  for (int k = 0; k < 600 && unplugsSeen(g.kiosk_log) == unplugs_before; ++k) sleepMs(100);
  sleepMs(pause_ms);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 6) {
    std::fprintf(stderr, "usage: %s DESCRIPTOR KIOSK_LOG LABEL CYCLES PAUSE_MS\n", argv[0]);
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  const std::vector<uint8_t> desc{std::istreambuf_iterator<char>(in), {}};
  const auto parsed = hid::parseReportDescriptor(desc.data(), desc.size());
  if (!parsed.descriptor) {
    std::fprintf(stderr, "KIOSK-PEN descriptor %s: %s\n", argv[1], parsed.error.c_str());
    return 1;
  }
  const auto found = hid::findPenLayout(*parsed.descriptor);
  if (!found.layout) {
    std::fprintf(stderr, "KIOSK-PEN no pen layout in %s\n", argv[1]);
    return 1;
  }
  const Plugger plugger{*found.layout, desc, argv[2], argv[3]};
  const int cycles = std::atoi(argv[4]);
  const int pause_ms = std::atoi(argv[5]);
  std::atomic<int> cycle{0};
  std::atomic<bool> watching{true};
  std::thread node_watch([&]() { watchNodes(plugger.label, cycle, watching); });
  for (int i = 1; i <= cycles; ++i) {
    if (!plugCycle(plugger, i, pause_ms, cycle)) {
      watching = false;
      node_watch.join();
      return 1;
    }
  }
  watching = false;
  node_watch.join();
  std::printf("KIOSK-PEN done %s\n", plugger.label.c_str());
  std::fflush(stdout);
  return 0;
}
