// Runs INSIDE the qemu guest (Debian's stock kernel, its own wacom and hid-uclogic drivers):
// makes tablets with uhid and with USB gadgets on dummy_hcd (configfs and GadgetFS), injects
// the pen script, and checks that the evdev backend and both hidapi backends report what was
// injected. Prints "CB-HIL CHECK ok|FAIL ..."
// lines, "CB-HIL FIGURE name value" lines and a final "CB-HIL RESULT PASS|FAIL".
//
//   cb_tablet_hil_vm FIXTURE_DIR DEVICE_DIR [uhid] [intuos4] [gadget] [latency] [corpus] [uclogic]
#include <fcntl.h>
#include <grp.h>
#include <linux/input.h>
#include <sys/ioctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "drivers/core/clock.h"
#include "drivers/core/pen_units.h"
#include "drivers/devices/device_file.h"
#include "drivers/evdev/evdev_node_survey.h"
#include "drivers/evdev/evdev_pen_source.h"
#include "drivers/evdev/uinput_latency.h"
#include "drivers/hid/hid_pen_layout.h"
#include "drivers/hid/hidapi_pen_source.h"
#include "drivers/hid/intuos4_decoder.h"
#include "drivers/usb/usb_devices.h"
#include "tests/hil/tablet/corpus_phase.h"
#include "tests/hil/tablet/hil_checks.h"
#include "tests/hil/tablet/hil_devices.h"
#include "tests/hil/tablet/intuos4_handbuilt.h"
#include "tests/hil/tablet/pen_script.h"
#include "tests/hil/tablet/uclogic_phase.h"
#include "tests/hil/tablet/uhid_device.h"
#include "tests/hil/tablet/usb_gadget.h"

namespace cb::hil {
namespace {

int g_failures = 0;

bool check(bool ok, const std::string& what) {
  std::printf("CB-HIL CHECK %s %s\n", ok ? "ok" : "FAIL", what.c_str());
  std::fflush(stdout);
  if (!ok) ++g_failures;
  return ok;
}

void figure(const std::string& name, double value) {
  std::printf("CB-HIL FIGURE %s %.3f\n", name.c_str(), value);
}

std::string describe(const PenSample& s) {
  char b[320];
  std::snprintf(b, sizeof b,
                "prox=%d tool=%d id=%#x serial=%#llx x=%d(%.3fmm) y=%d(%.3fmm) p=%d(%.4f) "
                "tilt=%d,%d(%.2f,%.2f deg) dist=%d(%.3f) buttons=%#x",
                s.in_proximity, static_cast<int>(s.tool), s.tool_id,
                static_cast<unsigned long long>(s.tool_serial), s.x_raw, s.x_mm, s.y_raw, s.y_mm,
                s.pressure_raw, s.pressure, s.tilt_x_raw, s.tilt_y_raw, s.tilt_x_deg, s.tilt_y_deg,
                s.distance_raw, s.distance, s.buttons);
  return b;
}

std::vector<uint8_t> readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Polls until at least one sample arrived (or the timeout), then drains briefly.
std::vector<PenSample> collect(PenSource& src, int timeout_ms) {
  std::vector<PenSample> got;
  const int64_t start = nowNs();
  while (got.empty() && nowNs() - start < int64_t{timeout_ms} * 1000000) {
    src.poll(10, got);
  }
  std::vector<PenSample> more;
  src.poll(5, more);
  got.insert(got.end(), more.begin(), more.end());
  return got;
}

bool sameInfo(const PenDeviceInfo& a, const PenDeviceInfo& b) {
  return a.x_max == b.x_max && a.y_max == b.y_max && a.x_res == b.x_res && a.y_res == b.y_res &&
         a.pressure_max == b.pressure_max && a.tilt_min == b.tilt_min && a.tilt_max == b.tilt_max &&
         a.tilt_res == b.tilt_res && a.distance_max == b.distance_max;
}

std::string describeInfo(const PenDeviceInfo& d) {
  char b[256];
  std::snprintf(b, sizeof b,
                "'%s' x 0..%d @%.1f/mm y 0..%d @%.1f/mm p 0..%d tilt %d..%d @%.4f/deg "
                "dist 0..%d",
                d.name, d.x_max, d.x_res, d.y_max, d.y_res, d.pressure_max, d.tilt_min, d.tilt_max,
                d.tilt_res, d.distance_max);
  return b;
}

// Injects the script through `inject` and checks every listed source in lockstep.
void runScript(const std::string& label, const std::vector<PenStep>& steps, bool intuos4,
               const PenDeviceInfo& info, const std::function<bool(const PenStep&, bool)>& inject,
               std::vector<PenSource*> sources, size_t limit = SIZE_MAX) {
  PenSample previous{};
  int mismatches = 0, samples = 0;
  bool was_in = false;
  for (size_t i = 0; i < steps.size() && i < limit; ++i) {
    const PenStep& st = steps[i];
    PenSample expected;
    const bool expect = expectedSample(st, info, intuos4, previous, expected);
    const bool entering = st.sense && !was_in;
    was_in = st.sense;
    if (!inject(st, entering)) {
      check(false, label + ": injecting step " + std::to_string(i));
      return;
    }
    for (PenSource* src : sources) {
      const bool is_evdev = std::string(src->backendName()) == "evdev";
      std::vector<PenSample> got = collect(*src, expect ? 1000 : 50);
      const bool ok = expect ? (got.size() == 1 && samePenState(got[0], expected)) : got.empty();
      if (!ok && mismatches < 6) {
        std::printf("  %s step %zu via %s: expected %s\n", label.c_str(), i, src->backendName(),
                    expect ? describe(expected).c_str() : "no sample");
        for (const PenSample& g : got)
          std::printf("  %s step %zu via %s:      got %s\n", label.c_str(), i, src->backendName(),
                      describe(g).c_str());
      }
      if (!ok) ++mismatches;
      if (expect && got.size() == 1 && is_evdev)
        check(got[0].t_ns > 0 && got[0].t_ns <= nowNs(),
              label + ": evdev timestamp is CLOCK_MONOTONIC");
      samples += static_cast<int>(got.size());
    }
  }
  check(mismatches == 0, label + ": every sample equals the injected motion (" +
                             std::to_string(samples) + " samples, " + std::to_string(mismatches) +
                             " mismatches)");
}

// Unplug in the middle of a stroke: every source must end the stroke and go back to searching.
void checkUnplug(const std::string& label, std::vector<PenSource*> sources) {
  for (PenSource* src : sources) {
    std::vector<PenSample> got;
    const int64_t start = nowNs();
    while (src->connection() == PenConnection::kConnected && nowNs() - start < 3'000'000'000)
      src->poll(20, got);
    const bool ended = !got.empty() && !got.back().in_proximity && got.back().buttons == 0;
    check(ended, label + ": unplug mid-stroke ends the stroke via " + src->backendName() + " (" +
                     std::to_string(got.size()) + " samples, last " +
                     (got.empty() ? std::string("none") : describe(got.back())) + ")");
    check(
        src->connection() == PenConnection::kSearching,
        label + ": " + src->backendName() + " is searching after unplug: " + src->statusMessage());
  }
}

void checkReplug(const std::string& label, std::vector<PenSource*> sources) {
  for (PenSource* src : sources) {
    int64_t took = 0;
    const bool ok = waitConnected(*src, 5000, &took);
    figure(label + "_replug_" + src->backendName() + "_ms", took / 1e6);
    check(ok && took <= 1'000'000'000, label + ": " + src->backendName() +
                                           " picks the tablet up again in " +
                                           std::to_string(took / 1000000) + " ms (limit 1000)");
  }
}

// Runs `what` in a child process as user nobody (no supplementary groups) and returns what it
// returned, or "setuid failed".
std::string asNobody(const std::function<std::string()>& what) {
  int pipefd[2];
  if (pipe(pipefd) != 0) return "pipe failed";
  const pid_t child = fork();
  if (child == 0) {
    close(pipefd[0]);
    std::string out = "setuid failed";
    if (setgroups(0, nullptr) == 0 && setgid(65534) == 0 && setuid(65534) == 0) out = what();
    (void)!write(pipefd[1], out.data(), out.size());
    _exit(0);
  }
  close(pipefd[1]);
  std::string out;
  char buf[512];
  for (ssize_t n; (n = read(pipefd[0], buf, sizeof buf)) > 0;) out.append(buf, n);
  close(pipefd[0]);
  waitpid(child, nullptr, 0);
  return out;
}

// Slow strokes: the input core's fuzz filter (drivers/input/input.c
// input_defuzz_abs_event) drops or smooths small changes on evdev; the hidraw backend applies
// the same filter by default. `reports` are injected back to back (well inside the driver's
// 100 ms idle-proximity timer), then every source's samples up to the first out-of-proximity
// one are compared field by field: `filtered` must give evdev's sequence exactly; `raw` (the
// filter off) must differ from evdev's, so the check can fail. (The wacom driver sends
// MSC_SERIAL with every report, so evdev gets a frame for each even when the filter holds every
// axis: reports are not dropped, values are held or smoothed.)
void checkSlowStroke(const std::string& label, const std::vector<std::vector<uint8_t>>& reports,
                     size_t pen_reports,
                     const std::function<bool(const std::vector<uint8_t>&)>& send, PenSource& evdev,
                     PenSource& filtered, PenSource& raw) {
  std::vector<PenSample> drained;
  for (PenSource* src : {&evdev, &filtered, &raw}) src->poll(20, drained);
  for (const std::vector<uint8_t>& r : reports) {
    if (!send(r)) {
      check(false, label + ": injecting a slow-stroke report");
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(4));
  }
  auto read = [](PenSource& src) {
    std::vector<PenSample> got, in;
    const int64_t start = nowNs();
    while (nowNs() - start < 400'000'000) src.poll(20, got);
    for (const PenSample& g : got) {
      if (!g.in_proximity) break;
      in.push_back(g);
    }
    return in;
  };
  const std::vector<PenSample> ev = read(evdev), hr = read(filtered), unfiltered = read(raw);
  size_t first_difference = 0;
  while (first_difference < std::min(ev.size(), hr.size()) &&
         samePenState(ev[first_difference], hr[first_difference]))
    ++first_difference;
  const bool same = ev.size() == hr.size() && first_difference == ev.size();
  if (!same && first_difference < std::max(ev.size(), hr.size())) {
    std::printf("  %s: sample %zu differs\n    evdev : %s\n    hidraw: %s\n", label.c_str(),
                first_difference,
                first_difference < ev.size() ? describe(ev[first_difference]).c_str() : "none",
                first_difference < hr.size() ? describe(hr[first_difference]).c_str() : "none");
  }
  figure(label + "_reports", double(reports.size()));
  figure(label + "_evdev_samples", double(ev.size()));
  check(same, label + ": " + std::to_string(reports.size()) + " slow-stroke reports give evdev " +
                  std::to_string(ev.size()) + " samples and filtered hidraw " +
                  std::to_string(hr.size()) + ", equal field by field");
  // With the filter off, the same reports must come out differently (held or smoothed
  // positions and tilts), so the comparison above can fail.
  size_t differing = unfiltered.size() == ev.size() ? 0 : std::max(ev.size(), unfiltered.size());
  for (size_t i = 0; unfiltered.size() == ev.size() && i < ev.size(); ++i)
    differing += samePenState(ev[i], unfiltered[i]) ? 0 : 1;
  figure(label + "_samples_changed_by_the_filter", double(differing));
  check(!ev.empty() && ev.size() <= pen_reports && differing > 0,
        label + ": without the filter (--raw) hidraw differs from evdev in " +
            std::to_string(differing) + " of " + std::to_string(ev.size()) + " samples (" +
            std::to_string(pen_reports) + " reports in proximity), so the check can fail");
}

// A slow stroke: pressed at `start`, small steps of 0–6 units on X and Y (many of at most 1,
// which fuzz 4 drops), pressure creeping by 1 and tilt and distance by 1 now and then (what a
// pen held nearly still gives).
std::vector<PenStep> slowStroke(PenStep start) {
  static const int dx[] = {0, 1, 1, 2, 0, 3, 1, 5, 1, 0, 4, 1, 2, 3, 0, 1, 6, 2, 1, 3};
  static const int dy[] = {1, 0, 1, 1, 1, 0, 3, 0, 2, 1, 0, 5, 1, 1, 2, 4, 0, 1, 3, 1};
  std::vector<PenStep> steps;
  PenStep s = start;
  s.in_range = s.sense = s.tip = true;
  s.eraser = s.invert = false;
  for (int i = 0; i < 40; ++i) {
    s.x += dx[i % 20];
    s.y += dy[(i + 7) % 20];
    if (i % 7 == 0) s.pressure += 1;
    if (i % 9 == 4) s.tilt_x += 1;
    if (i % 11 == 2) s.tilt_y -= 1;
    if (i % 13 == 6) s.distance += 1;
    steps.push_back(s);
  }
  return steps;
}

// Slow strokes: X/Y fuzz 4 (config/devices/wacom-generic.toml, the wacom driver's generic pen
// path), evdev against the filtered hidraw path.
void checkPth660SlowStroke(UhidDevice& dev, const hid::PenLayout& layout, const PenStep& start,
                           EvdevPenSource& evdev, hid::HidapiPenSource& hidraw) {
  hid::HidapiPenSourceOptions raw_options = hidOptions(hid::HidapiBackend::kHidraw, 0x056A);
  raw_options.input_fuzz = false;
  hid::HidapiPenSource raw(raw_options);
  if (check(waitConnected(raw, 5000), "uhid: a second hidraw reader without the filter opens")) {
    std::vector<std::vector<uint8_t>> reports;
    for (const PenStep& st : slowStroke(start)) reports.push_back(encodePenReport(layout, st));
    PenStep out = start;
    out.in_range = out.sense = out.tip = false;
    reports.push_back(encodePenReport(layout, out));
    checkSlowStroke(
        "uhid-pth660 slow stroke", reports, reports.size() - 1,
        [&](const std::vector<uint8_t>& r) { return dev.input(r); }, evdev, hidraw, raw);
  }
}

// An unprivileged user (no udev rule installed) gets a state naming the rule, not an exit.
void checkUnprivilegedStates() {
  int pipefd[2];
  if (pipe(pipefd) == 0) {
    pid_t child = fork();
    if (child == 0) {
      close(pipefd[0]);
      std::string verdict = "setuid failed";
      if (setgroups(0, nullptr) == 0 && setgid(65534) == 0 && setuid(65534) == 0) {
        EvdevPenSource e({});
        hid::HidapiPenSource h(hidOptions(hid::HidapiBackend::kHidraw, 0x056A));
        verdict = std::string(penConnectionName(e.connection())) + "|" + e.statusMessage() + "|" +
                  penConnectionName(h.connection()) + "|" + h.statusMessage();
      }
      (void)!write(pipefd[1], verdict.data(), verdict.size());
      _exit(0);
    }
    close(pipefd[1]);
    std::string verdict;
    char buf[512];
    for (ssize_t n; (n = read(pipefd[0], buf, sizeof buf)) > 0;) verdict.append(buf, n);
    close(pipefd[0]);
    waitpid(child, nullptr, 0);
    const size_t bar = verdict.find('|', verdict.find('|') + 1);
    const std::string ev = verdict.substr(0, bar),
                      hr = bar == std::string::npos ? "" : verdict.substr(bar + 1);
    check(ev.rfind("permission-denied|", 0) == 0 &&
              ev.find("70-cloudbrush-tablet.rules") != std::string::npos,
          "uhid: as an unprivileged user evdev reports permission denied naming the udev rule (" +
              ev + ")");
    check(hr.rfind("permission-denied|", 0) == 0 &&
              hr.find("70-cloudbrush-tablet.rules") != std::string::npos,
          "uhid: as an unprivileged user hidraw reports permission denied naming the udev rule (" +
              hr + ")");
  }
}

// What `cloudbrush devices` reports to that user: the event nodes (or /dev/input itself)
// closed to it, each with the error.
void checkUnprivilegedSurvey() {
  const std::string survey = asNobody([] {
    const EvdevSurvey s = surveyEvdevNodes();
    if (!s.dir_error.empty())
      return std::string(s.dir_permission_denied ? "dir-denied " : "dir-error ") + s.dir + ": " +
             s.dir_error;
    int denied = 0;
    std::string first;
    for (const EvdevNodeReport& n : s.nodes) {
      if (n.kind == EvdevNodeKind::kCannotOpen && n.permission_denied) ++denied;
      if (first.empty() && n.kind == EvdevNodeKind::kCannotOpen) first = n.path + ": " + n.detail;
    }
    return std::string(denied > 0 && denied == static_cast<int>(s.nodes.size()) ? "nodes-denied "
                                                                                : "nodes ") +
           std::to_string(denied) + "/" + std::to_string(s.nodes.size()) + " " + first;
  });
  const bool named =
      (survey.rfind("dir-denied ", 0) == 0 || survey.rfind("nodes-denied ", 0) == 0) &&
      survey.find("Permission denied") != std::string::npos;
  check(named, "uhid: as an unprivileged user the device survey names what is closed and why (" +
                   survey + ")");
}

// Overflow evdev's buffer (a stalled consumer): SYN_DROPPED, then libevdev's resync must leave
// the source with the device's true state.
void checkOverflowResync(UhidDevice& dev, const hid::PenLayout& layout, const PenStep& start,
                         const PenDeviceInfo& info, EvdevPenSource& evdev,
                         hid::HidapiPenSource& hidraw) {
  PenStep st = start;
  for (int i = 0; i < 300; ++i) {
    st.x = 1000 + 37 * i;
    st.pressure = (i * 53) % info.pressure_max;
    dev.input(encodePenReport(layout, st));
  }
  // Read at once: the wacom driver forces the pen out of proximity 100 ms after its last report.
  std::vector<PenSample> got;
  evdev.poll(0, got);
  check(evdev.resyncCount() >= 1,
        "uhid: evdev overflow reported SYN_DROPPED and libevdev resynced (" +
            std::to_string(evdev.resyncCount()) + " resyncs, " + std::to_string(got.size()) +
            " of 300 samples)");
  const bool final_seen = !got.empty() && got.back().in_proximity && got.back().x_raw == st.x &&
                          got.back().pressure_raw == st.pressure && got.back().tipDown();
  check(final_seen, "uhid: after the resync the sample is the device's final state" +
                        (got.empty() ? std::string() : " (" + describe(got.back()) + ")"));
  // The pen stops reporting without leaving: the kernel's idle-proximity timer ends the stroke
  // on evdev; the hidraw backend's own idle timeout must do the same. (hidraw keeps only the
  // first 64 of the 300 queued reports.)
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  for (PenSource* src : {static_cast<PenSource*>(&evdev), static_cast<PenSource*>(&hidraw)}) {
    std::vector<PenSample> out;
    for (int i = 0; i < 60; ++i) src->poll(5, out);
    check(!out.empty() && !out.back().in_proximity && out.back().buttons == 0,
          std::string("uhid: a pen that stops reporting leaves proximity via ") +
              src->backendName() + (out.empty() ? "" : " (" + describe(out.back()) + ")"));
  }
}

void phaseUhidPth660(const std::string& fixtures) {
  const std::vector<uint8_t> desc = readFile(fixtures + "/wacom-pth660_v145.rdesc");
  auto parsed = hid::parseReportDescriptor(desc.data(), desc.size());
  if (!check(parsed.descriptor.has_value(),
             "uhid: PTH-660 fixture descriptor parses " + parsed.error))
    return;
  auto layout = hid::findPenLayout(*parsed.descriptor);
  if (!check(layout.layout.has_value(), "uhid: PTH-660 pen layout found")) return;

  UhidDevice dev;
  std::string error;
  const int64_t t0 = nowNs();
  if (!check(dev.create("Wacom Intuos Pro M", desc, BUS_USB, 0x056A, 0x0357, &error),
             "uhid: UHID_CREATE2 " + error))
    return;
  EvdevPenSource evdev({});
  if (bool ok = waitConnected(evdev, 5000);
      !check(ok, "uhid: evdev finds the wacom Pen node: " + evdev.statusMessage()))
    return;
  figure("uhid_create_to_evdev_ms", (nowNs() - t0) / 1e6);
  hid::HidapiPenSource hidraw(hidOptions(hid::HidapiBackend::kHidraw, 0x056A));
  if (bool ok = waitConnected(hidraw, 5000);
      !check(ok, "uhid: hidapi-hidraw opens the tablet: " + hidraw.statusMessage()))
    return;
  const PenDeviceInfo info = evdev.deviceInfo();
  std::printf("  evdev : %s\n  hidraw: %s\n", describeInfo(info).c_str(),
              describeInfo(hidraw.deviceInfo()).c_str());
  check(std::string(info.name).find("Pen") != std::string::npos, "uhid: evdev node is the Pen");
  check(sameInfo(info, hidraw.deviceInfo()),
        "uhid: ranges and resolutions from the descriptor equal the kernel's absinfo");
  // The serial the device reports (UHID_CREATE2's uniq; session.json's device.serial).
  std::string why;
  const std::string evdev_serial = evdev.serialNumber(&why);
  check(evdev_serial == "cb-hil",
        "uhid: evdev reports the device's serial: '" + evdev_serial + "' " + why);
  const std::string hidraw_serial = hidraw.serialNumber(&why);
  check(hidraw_serial == "cb-hil",
        "uhid: hidapi-hidraw reports the device's serial: '" + hidraw_serial + "' " + why);

  auto inject = [&](const PenStep& s, bool) {
    return dev.input(encodePenReport(*layout.layout, s));
  };
  const auto steps = penScript(info.x_max, info.y_max, info.pressure_max, info.distance_max);
  runScript("uhid-pth660", steps, false, info, inject, {&evdev, &hidraw});

  checkPth660SlowStroke(dev, *layout.layout, steps[6], evdev, hidraw);
  checkUnprivilegedStates();
  checkUnprivilegedSurvey();
  checkOverflowResync(dev, *layout.layout, steps[6], info, evdev, hidraw);

  // Unplug mid-stroke (pen pressed), replug.
  runScript("uhid-pth660 before unplug", steps, false, info, inject, {&evdev, &hidraw}, 7);
  dev.destroy();
  checkUnplug("uhid", {&evdev, &hidraw});
  if (!check(dev.create("Wacom Intuos Pro M", desc, BUS_USB, 0x056A, 0x0357, &error),
             "uhid: recreate"))
    return;
  checkReplug("uhid", {&evdev, &hidraw});
  runScript("uhid-pth660 after replug", steps, false, info, inject, {&evdev, &hidraw}, 8);
  dev.destroy();
  std::vector<PenSample> drain;
  evdev.poll(100, drain);
  hidraw.poll(100, drain);
}

void phaseUhidIntuos4() {
  // The descriptor is HAND-BUILT (no real Intuos4 descriptor is available): see
  // intuos4_handbuilt.h. The kernel picks the Intuos4 protocol from the USB id 056a:00b9.
  UhidDevice dev;
  constexpr uint8_t kModeReport = 2, kTabletMode = 2;  // config/devices/wacom-intuos4.toml
  dev.setFeature(kModeReport, {0});                    // powers up in mouse mode
  std::string error;
  if (!check(dev.create("Wacom Intuos4 6x9", handBuiltIntuos4Descriptor(), BUS_USB, 0x056A, 0x00B9,
                        &error),
             "intuos4: UHID_CREATE2 with the hand-built descriptor " + error))
    return;
  EvdevPenSource evdev({});
  if (bool ok = waitConnected(evdev, 5000);
      !check(ok, "intuos4: evdev finds the pen: " + evdev.statusMessage()))
    return;
  // The kernel's wacom driver sets feature 2 := 2 itself after binding (wacom_query_tablet_data,
  // retried until a GET returns 2), about a second later. A check that merely sees a SET 2=2
  // cannot tell that switch from the backend's, so first let the kernel's finish: wait for its
  // SET (up to 4 s), then until no SET has come for 1.5 s.
  {
    const int64_t start = nowNs();
    size_t seen = 0;
    int64_t last_change = start;
    while (nowNs() - start < 8'000'000'000) {
      const size_t n = dev.setReports().size();
      if (n != seen) seen = n, last_change = nowNs();
      const bool kernel_done = n > 0 || nowNs() - start > 4'000'000'000;
      if (kernel_done && nowNs() - last_change > 1'500'000'000) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  std::string kernel_sets;
  for (const auto& r : dev.setReports())
    if (!r.empty())
      kernel_sets += " " + std::to_string(r[0]) + (r.size() > 1 ? "=" + std::to_string(r[1]) : "");
  std::printf("  intuos4: SET_REPORTs from the kernel's wacom driver after binding:%s\n",
              kernel_sets.empty() ? " none" : kernel_sets.c_str());
  // Back to mouse mode. Control: a hidraw backend told not to switch must leave it there for as
  // long as the switching backend below takes, and longer (nothing else switches it now). If
  // this fails, the kernel is still switching and the next check would prove nothing.
  dev.setFeature(kModeReport, {0});
  const size_t sets_before_control = dev.setReports().size();
  {
    hid::HidapiPenSourceOptions quiet = hidOptions(hid::HidapiBackend::kHidraw, 0x056A);
    quiet.switch_mode = false;
    hid::HidapiPenSource control(quiet);
    waitConnected(control, 5000);
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    const auto f = dev.feature(kModeReport);
    check(dev.setReports().size() == sets_before_control && !f.empty() && f[0] == 0,
          "intuos4: control: a hidraw backend that does not switch leaves mode 0, no SET_REPORT "
          "for 1.5 s (" +
              std::to_string(dev.setReports().size() - sets_before_control) +
              " arrived): " + control.statusMessage());
  }
  // The backend under test switches inside its constructor (tryOpen -> ensureTabletMode); the
  // SET must arrive while it runs, and be the only one.
  const size_t sets_before = dev.setReports().size();
  const int64_t open_start = nowNs();
  hid::HidapiPenSource hidraw(hidOptions(hid::HidapiBackend::kHidraw, 0x056A));
  const int64_t open_end = nowNs();
  if (bool ok = waitConnected(hidraw, 5000);
      !check(ok, "intuos4: hidapi-hidraw opens it: " + hidraw.statusMessage()))
    return;
  {
    const auto sets = dev.setReports();
    const auto times = dev.setReportTimes();
    bool inside = sets.size() == sets_before + 1;
    for (size_t i = sets_before; i < sets.size() && inside; ++i)
      inside = times[i] >= open_start && times[i] <= open_end && sets[i].size() >= 2 &&
               sets[i][0] == kModeReport && sets[i][1] == kTabletMode;
    const auto f = dev.feature(kModeReport);
    check(inside && !f.empty() && f[0] == kTabletMode,
          "intuos4: hidraw backend switched the tablet to mode 2 itself (" +
              std::to_string(sets.size() - sets_before) + " SET_REPORT(s), within the " +
              std::to_string((open_end - open_start) / 1000000) +
              " ms the backend took to open): " + hidraw.statusMessage());
  }
  check(hidraw.device().protocol == "intuos4", "intuos4: hidraw backend uses the Intuos4 decoder");
  const PenDeviceInfo info = evdev.deviceInfo();
  std::printf("  evdev : %s\n  hidraw: %s\n", describeInfo(info).c_str(),
              describeInfo(hidraw.deviceInfo()).c_str());
  check(sameInfo(info, hidraw.deviceInfo()), "intuos4: ranges equal the kernel's absinfo");
  auto inject = [&](const PenStep& s, bool entering) {
    if (!s.sense) return dev.input(encodeIntuos4Exit());
    if (entering && !dev.input(encodeIntuos4Enter(s.tool_type, s.serial))) return false;
    return dev.input(encodeIntuos4Pen(s));
  };
  const auto script = penScript(info.x_max, info.y_max, info.pressure_max, info.distance_max);
  runScript("intuos4", script, true, info, inject, {&evdev, &hidraw});

  // Slow strokes: the Intuos protocol's fuzz (config/devices/wacom-intuos4.toml: X/Y 4, tilt
  // and distance 1), evdev against the filtered hidraw path.
  {
    hid::HidapiPenSourceOptions raw_options = hidOptions(hid::HidapiBackend::kHidraw, 0x056A);
    raw_options.input_fuzz = false;
    raw_options.switch_mode = false;  // already in tablet mode
    hid::HidapiPenSource raw(raw_options);
    if (check(waitConnected(raw, 5000), "intuos4: a second hidraw reader without the filter")) {
      const PenStep start = script[6];
      std::vector<std::vector<uint8_t>> reports = {
          encodeIntuos4Enter(start.tool_type, start.serial)};
      for (const PenStep& st : slowStroke(start)) reports.push_back(encodeIntuos4Pen(st));
      reports.push_back(encodeIntuos4Exit());
      checkSlowStroke(
          "intuos4 slow stroke", reports, reports.size() - 2,
          [&](const std::vector<uint8_t>& r) { return dev.input(r); }, evdev, hidraw, raw);
    }
  }
  dev.destroy();
}

void phaseGadget(const std::string& fixtures) {
  const std::vector<uint8_t> desc = readFile(fixtures + "/wacom-pth660_v145.rdesc");
  auto parsed = hid::parseReportDescriptor(desc.data(), desc.size());
  auto layout = hid::findPenLayout(*parsed.descriptor);
  UsbGadget gadget;
  GadgetConfig config;
  config.report_descriptor = desc;
  std::string error;
  if (!check(gadget.create("cbpen", config, &error),
             "gadget: configfs gadget 056a:0357 " + error) ||
      !check(gadget.bind(&error), "gadget: bound to the dummy UDC " + error))
    return;
  PenDeviceInfo evdev_info{};
  {
    EvdevPenSource evdev({});
    if (bool ok = waitConnected(evdev, 10000);
        !check(ok, "gadget: evdev finds the USB tablet: " + evdev.statusMessage()))
      return;
    hid::HidapiPenSource hidraw(hidOptions(hid::HidapiBackend::kHidraw, 0x056A));
    if (bool ok = waitConnected(hidraw, 5000);
        !check(ok, "gadget: hidapi-hidraw opens it: " + hidraw.statusMessage()))
      return;
    evdev_info = evdev.deviceInfo();
    auto usb = usb::listUsbDevices(0x056A);
    bool seen = false;
    for (const auto& d : usb) {
      std::printf("  libusb: %04x:%04x bus %d addr %d '%s' '%s' serial '%s' %s\n", d.vendor,
                  d.product, d.bus, d.address, d.manufacturer.c_str(), d.product_name.c_str(),
                  d.serial.c_str(), d.open_error.c_str());
      seen |=
          d.product == 0x0357 && d.serial == config.serial && d.product_name == config.product_name;
    }
    check(seen, "gadget: libusb reports the identity 056a:0357, product and serial");
    auto inject = [&](const PenStep& s, bool) {
      std::string e;
      return gadget.send(encodePenReport(*layout.layout, s), 1000, &e);
    };
    runScript("gadget",
              penScript(evdev_info.x_max, evdev_info.y_max, evdev_info.pressure_max,
                        evdev_info.distance_max),
              false, evdev_info, inject, {&evdev, &hidraw});
  }
  // The libusb backend: hidapi detaches the kernel driver and talks to the endpoint itself.
  hid::HidapiPenSource libusb(hidOptions(hid::HidapiBackend::kLibusb, 0x056A));
  if (bool ok = waitConnected(libusb, 5000);
      !check(ok, "gadget: hidapi-libusb opens the tablet: " + libusb.statusMessage()))
    return;
  check(sameInfo(evdev_info, libusb.deviceInfo()),
        "gadget: libusb-side ranges equal the kernel's absinfo");
  auto inject = [&](const PenStep& s, bool) {
    std::string e;
    return gadget.send(encodePenReport(*layout.layout, s), 1000, &e);
  };
  const auto steps = penScript(evdev_info.x_max, evdev_info.y_max, evdev_info.pressure_max,
                               evdev_info.distance_max);
  runScript("gadget-libusb", steps, false, evdev_info, inject, {&libusb});
  runScript("gadget-libusb before unplug", steps, false, evdev_info, inject, {&libusb}, 7);
  check(gadget.unbind(&error), "gadget: UDC unbind (unplug) " + error);
  checkUnplug("gadget", {&libusb});
  check(gadget.bind(&error), "gadget: UDC bind (replug) " + error);
  // The replug counts from the moment the emulated kernel has enumerated the device (it shows
  // up in sysfs); the enumeration itself, slow under TCG, is not the driver's to speed up.
  const int64_t bound = nowNs();
  while (access("/sys/bus/usb/devices/1-1/idVendor", F_OK) != 0 && nowNs() - bound < 5'000'000'000)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  figure("gadget_bind_to_enumerated_ms", (nowNs() - bound) / 1e6);
  checkReplug("gadget", {&libusb});
  runScript("gadget-libusb after replug", steps, false, evdev_info, inject, {&libusb}, 8);
}

double percentileOf(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p / 100.0 * (v.size() - 1) + 0.5))];
}

// The host benchmark's latency probe, run here on the emulated machine (uinput -> evdev ->
// consumer thread). TCG emulation makes these figures pessimistic; they are labelled emulated.
void phaseLatency() {
  EvdevLatencyResult r = measureEvdevLatency(1000, 500.0);
  if (!check(r.ran, "latency: uinput probe ran " + r.error)) return;
  check(r.delay_us.size() >= 990,
        "latency: consumer received " + std::to_string(r.delay_us.size()) + " of 1000 samples");
  figure("vm_uinput_delay_p50_us", percentileOf(r.delay_us, 50));
  figure("vm_uinput_delay_p99_us", percentileOf(r.delay_us, 99));
  figure("vm_thread_wakeup_p50_us", percentileOf(r.wakeup_us, 50));
  figure("vm_thread_wakeup_p99_us", percentileOf(r.wakeup_us, 99));
}

}  // namespace
}  // namespace cb::hil

int main(int argc, char** argv) {
  using namespace cb::hil;
  if (argc < 3) {
    std::fprintf(
        stderr,
        "usage: %s FIXTURE_DIR DEVICE_DIR [uhid] [intuos4] [gadget] [latency] [corpus] [uclogic]\n",
        argv[0]);
    return 2;
  }
  const std::string fixtures = argv[1];
  {
    const cb::DeviceFileLoad load = cb::loadDeviceDirectory(argv[2]);
    check(load.errors.empty() && !load.database->entries().empty(),
          "device files load from " + std::string(argv[2]) +
              (load.errors.empty() ? "" : ": " + load.errors.front()));
    hilDevices() = load.database;
  }
  std::vector<std::string> phases(argv + 3, argv + argc);
  if (phases.empty()) phases = {"uhid", "intuos4", "gadget", "latency", "corpus", "uclogic"};
  for (const std::string& p : phases) {
    std::printf("CB-HIL PHASE %s\n", p.c_str());
    std::fflush(stdout);
    if (p == "uhid")
      phaseUhidPth660(fixtures);
    else if (p == "intuos4")
      phaseUhidIntuos4();
    else if (p == "gadget")
      phaseGadget(fixtures);
    else if (p == "latency")
      phaseLatency();
    else if (p == "corpus")
      g_failures += runCorpusPhase(fixtures);
    else if (p == "uclogic")
      g_failures += runUclogicPhase(fixtures);
    else
      check(false, "unknown phase " + p);
  }
  std::printf("CB-HIL RESULT %s (%d failed checks)\n", g_failures ? "FAIL" : "PASS", g_failures);
  std::fflush(stdout);
  return g_failures ? 1 : 0;
}
