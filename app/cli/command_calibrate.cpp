// `cloudbrush calibrate`: the pen-driven N-point calibration.
//
// Interactive (default): targets are drawn on the display one at a time (corners and centre,
// or a 3x3 grid); the participant taps each with the pen; the correction is fitted (homography
// or affine) and the residual of every point is shown in pixels; tapping the green box (or
// Space) accepts and saves the profile for this tablet under the state directory, the orange
// box redoes, Esc leaves without saving. The whole session is recorded as a journal (device,
// screen, targets as markers, raw pen samples, the accepted profile), so it can be re-fitted.
//
// Non-interactive: --points FILE fits a tap file (calibration/n_point_calibration.h);
// --journal FILE re-fits a recorded calibration session. Both print the fit and, with --save,
// write the profile.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "app/shell/keymap.h"
#include "app/shell/ui_overlay.h"

#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/core/config_paths.h"
#include "app/render/gl/display.h"
#include "app/render/image_io.h"
#include "app/shell/keymap.h"
#include "app/shell/ui_overlay.h"
#include "calibration/area_mapping.h"
#include "calibration/n_point_calibration.h"
#include "calibration/nib_offset.h"
#include "calibration/point_fit.h"
#include "calibration/pressure_range.h"
#include "calibration/profile_store.h"
#include "drivers/core/journal.h"
#include "drivers/open_pen_source.h"

namespace cb {
namespace {

int usage(int code) {
  std::printf(
      "usage: cloudbrush calibrate [OPTIONS]\n"
      "\n"
      "Pen-driven N-point calibration: tap each target with the pen, check the residuals,\n"
      "accept (green box or Space) or redo (orange box); Esc leaves without saving. The profile\n"
      "is saved for this tablet under the state directory and used from then on.\n"
      "\n"
      "  --targets 5|9         corners and centre, or a 3x3 grid (default 9)\n"
      "  --fit homography|affine   correction model (default homography)\n"
      "  --backend NAME        pen backend: auto, evdev, hidraw, libusb, replay (default auto)\n"
      "  --device PATH         event node, hidapi path, or the journal for --backend replay\n"
      "  --display NAME        auto, kms, x11, surfaceless (default auto)\n"
      "  --per-tool            save the profile for this pen's serial only\n"
      "  --yes                 accept the first fit without asking (unattended runs)\n"
      "  --record FILE         journal of the session (default STATE/calibration-<time>.cbj;\n"
      "                        with --pressure only when given)\n"
      "  --snapshot FILE.png   save the result screen (targets, taps, residuals) as a PNG\n"
      "  --timeout S           give up after S seconds without finishing (default 300)\n"
      "  --pressure            the participant's press calibration instead: press lightly, lift,\n"
      "                        press firmly, lift; prints the [pressure_range] for the session\n"
      "  --session-out FILE    with --pressure: also write the [pressure_range] to FILE\n"
      "  --points FILE         non-interactive: fit the taps in a tap file (TOML)\n"
      "  --journal FILE        non-interactive: re-fit a recorded calibration session\n"
      "  --save                with --points/--journal: save the fitted profile\n"
      "  --config-dir DIR      shipped defaults (default: the config/ directory)\n"
      "  --state-dir DIR       where kiosk profiles are saved (default: the state directory)\n");
  return code;
}

struct Settings {
  int targets = 9;
  PointFitKind fit = PointFitKind::kHomography;
  std::string config_dir, state_dir;
  bool per_tool = false;
};

// The profile whose area mapping the taps are measured against: the one in force for this
// device, with its old correction removed.
CalibrationProfile baseProfile(const PenDeviceInfo& device, uint64_t serial, const Settings& s) {
  ProfileSelection sel = selectProfile(device, serial, s.config_dir, s.state_dir);
  for (const auto& m : sel.messages) std::fprintf(stderr, "calibrate: %s\n", m.c_str());
  std::printf("area mapping from %s\n", sel.source.c_str());
  CalibrationProfile p = sel.profile;
  p.fit_kind = PointFitKind::kNone;
  p.correction = glm::dmat3(1.0);
  p.fit_rms_px = p.fit_max_px = 0.0;
  p.fit_points = 0;
  return p;
}

void printFit(const CalibrationFit& fit, const std::vector<Tap>& taps) {
  std::printf("%s fit over %zu points:\n", pointFitKindName(fit.profile.fit_kind), taps.size());
  for (size_t i = 0; i < taps.size() && i < fit.fit.residuals.size(); ++i) {
    std::printf("  target %zu at (%.0f, %.0f) px: tap at (%.2f, %.2f) mm, residual %.2f px\n", i,
                taps[i].target_px.x, taps[i].target_px.y, taps[i].pen_mm.x, taps[i].pen_mm.y,
                fit.fit.residuals[i]);
  }
  std::printf("residual: rms %.3f px, max %.3f px\n", fit.fit.rms, fit.fit.max_residual);
}

int saveFit(const CalibrationFit& fit, const Settings& s, std::string* saved_path) {
  std::string error;
  const std::string path = saveProfile(fit.profile, s.state_dir, &error);
  if (path.empty()) {
    std::fprintf(stderr, "calibrate: %s\n", error.c_str());
    return 1;
  }
  std::printf("saved %s\n", path.c_str());
  if (saved_path) *saved_path = path;
  return 0;
}

CalibrationFit fitTaps(const PenDeviceInfo& device, uint64_t serial, int w, int h,
                       const std::vector<Tap>& taps, const Settings& s) {
  CalibrationProfile base = baseProfile(device, s.per_tool ? serial : 0, s);
  return fitCalibration(base, device, s.per_tool ? serial : 0, w, h, taps, s.fit);
}

// --points FILE
int runPointsFile(const std::string& path, const Settings& s, bool save) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "calibrate: %s: cannot be opened\n", path.c_str());
    return 2;
  }
  std::stringstream ss;
  ss << in.rdbuf();
  std::string error;
  std::optional<TapFile> file = parseTapFile(ss.str(), path, &error);
  if (!file) {
    std::fprintf(stderr, "calibrate: %s\n", error.c_str());
    return 2;
  }
  CalibrationFit fit = fitTaps(file->device, 0, file->screen_w, file->screen_h, file->taps, s);
  if (!fit.ok) {
    std::fprintf(stderr, "calibrate: %s: %s\n", path.c_str(), fit.error.c_str());
    return 1;
  }
  printFit(fit, file->taps);
  return save ? saveFit(fit, s, nullptr) : 0;
}

// Markers written by the interactive session and read back by --journal.
std::string screenMarker(int w, int h) {
  return "calibrate screen " + std::to_string(w) + " " + std::to_string(h);
}
std::string targetMarker(size_t i, glm::dvec2 t) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "calibrate target %zu %.17g %.17g", i, t.x, t.y);
  return buf;
}

// --journal FILE: device, screen and targets from the records, taps from the raw samples.
int runJournal(const std::string& path, const Settings& s, bool save) {
  JournalReadResult j = readJournal(path);
  if (!j.error.empty()) std::fprintf(stderr, "calibrate: %s\n", j.error.c_str());
  std::optional<PenDeviceInfo> device;
  int w = 0, h = 0;
  std::vector<glm::dvec2> targets;
  std::vector<Tap> taps;
  TapCollector collector;
  uint64_t serial = 0;
  for (const JournalRecord& r : j.records) {
    if (r.type == JournalRecordType::kDevice) {
      device = decodeDeviceInfo(r.payload);
    } else if (r.type == JournalRecordType::kMarker) {
      std::istringstream in{std::string(r.text())};
      std::string word, what;
      in >> word >> what;
      if (word != "calibrate") continue;
      if (what == "screen") {
        in >> w >> h;
      } else if (what == "target") {
        size_t i = 0;
        glm::dvec2 t;
        if (in >> i >> t.x >> t.y && i == targets.size()) targets.push_back(t);
      } else if (what == "redo") {
        taps.clear();
      }
    } else if (r.type == JournalRecordType::kPenSample && device) {
      std::optional<PenSample> sample = decodePenSample(r.payload);
      if (!sample) continue;
      if (sample->tool_serial) serial = sample->tool_serial;
      if (auto tap = collector.feed(*sample, device->pressure_max > 0)) {
        if (taps.size() < targets.size()) taps.push_back({targets[taps.size()], *tap});
      }
    }
  }
  if (!device || w <= 0 || h <= 0 || targets.empty()) {
    std::fprintf(stderr,
                 "calibrate: %s: not a calibration journal (needs a device record and "
                 "'calibrate screen' / 'calibrate target' markers)\n",
                 path.c_str());
    return 2;
  }
  if (taps.size() < targets.size()) {
    std::fprintf(stderr, "calibrate: %s: %zu taps for %zu targets\n", path.c_str(), taps.size(),
                 targets.size());
    return 1;
  }
  CalibrationFit fit = fitTaps(*device, serial, w, h, taps, s);
  if (!fit.ok) {
    std::fprintf(stderr, "calibrate: %s: %s\n", path.c_str(), fit.error.c_str());
    return 1;
  }
  printFit(fit, taps);
  return save ? saveFit(fit, s, nullptr) : 0;
}

// ---- Drawing: filled rectangles by scissored clears (no shaders needed for a calibration
// screen); words through the shell's UiOverlay (one font for every screen). y is measured from
// the top.

class Painter {
 public:
  Painter(int w, int h) : w_(w), h_(h) {}
  void clear(float r, float g, float b) {
    glDisable(GL_SCISSOR_TEST);
    glClearColor(r, g, b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
  }
  void rect(double x, double y, double w, double h, float r, float g, float b) {
    const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
    const int x1 = static_cast<int>(std::ceil(x + w)), y1 = static_cast<int>(std::ceil(y + h));
    if (x1 <= 0 || y1 <= 0 || x0 >= w_ || y0 >= h_) return;
    glEnable(GL_SCISSOR_TEST);
    glScissor(x0, h_ - y1, x1 - x0, y1 - y0);  // GL's origin is bottom-left
    glClearColor(r, g, b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
  }
  void crosshair(glm::dvec2 c, double size, float r, float g, float b) {
    rect(c.x - size, c.y - 1, 2 * size, 3, r, g, b);
    rect(c.x - 1, c.y - size, 3, 2 * size, r, g, b);
  }

 private:
  int w_, h_;
};

struct Button {
  double x, y, w, h;
  bool contains(glm::dvec2 p) const { return p.x >= x && p.x < x + w && p.y >= y && p.y < y + h; }
};

std::string defaultRecordPath(const std::string& state_dir) {
  char stamp[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::gmtime(&now));
  return (std::filesystem::path(state_dir) / (std::string("calibration-") + stamp + ".cbj"))
      .string();
}

// The pen and the display of an interactive session, opened and waited for.
struct InteractiveIo {
  std::unique_ptr<PenSource> pen;
  std::unique_ptr<Display> display;
  UiOverlay ui;
  int w = 0, h = 0;
  // Draws the words of a calibration screen (a title and lines below it, centred).
  void say(const std::vector<std::string>& lines, float top = 0.12f) {
    std::vector<UiLabel> labels;
    const float size = std::max(18.0f, float(h) / 30.0f);
    for (size_t i = 0; i < lines.size(); ++i)
      labels.push_back({float(w) * 0.5f, float(h) * top + float(i) * size * 1.5f, lines[i],
                        i == 0 ? size * 1.3f : size, i == 0 ? 0xffffffffu : 0xd0d8e0ffu, true});
    ui.drawLabels(w, h, labels);
  }
};

// Opens both, shows a dark red screen until the pen is connected. Returns an exit code on
// failure, 0 when ready.
int openInteractive(const Args& args, double timeout_s, InteractiveIo* io) {
  PenSourceOptions po;
  po.backend = args.get("backend", "auto");
  po.device = args.get("device", "");
  po.realtime = false;  // replays are fed as fast as the loop takes them
  po.device_dir = configFile("devices");
  std::string error;
  io->pen = openPenSource(po, &error);
  if (!io->pen) {
    std::fprintf(stderr, "calibrate: %s\n", error.c_str());
    return 2;
  }
  DisplayOptions dopt;
  if (auto d = args.get("display")) {
    if (!parseDisplayPlatform(*d, &dopt.platform)) {
      std::fprintf(stderr, "calibrate: --display %s is not auto, kms, x11 or surfaceless\n",
                   d->c_str());
      return 2;
    }
  }
  std::string note;
  io->display = openDisplay(dopt, &error, &note);
  if (!io->display) {
    std::fprintf(stderr, "calibrate: no display: %s\n", error.c_str());
    return 2;
  }
  if (!note.empty()) std::printf("display: %s\n", note.c_str());
  if (!io->display->makeCurrent(&error)) {
    std::fprintf(stderr, "calibrate: %s\n", error.c_str());
    return 2;
  }
  io->w = io->display->width();
  io->h = io->display->height();
  std::printf("display %s %dx%d, pen backend %s\n", io->display->platformName(), io->w, io->h,
              io->pen->backendName());
  if (!io->ui.init(&error))
    std::fprintf(stderr, "calibrate: on-screen text unavailable: %s\n", error.c_str());
  const auto start = std::chrono::steady_clock::now();
  std::vector<PenSample> ignored;
  if (io->pen->connection() != PenConnection::kConnected)
    std::fprintf(stderr,
                 "calibrate: waiting for the pen (%s): connect the tablet and bring the pen near "
                 "it; Esc quits\n",
                 io->pen->statusMessage().c_str());
  while (io->pen->connection() != PenConnection::kConnected) {
    const double waited =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (io->pen->connection() == PenConnection::kPermissionDenied ||
        io->pen->connection() == PenConnection::kFinished || waited > timeout_s) {
      std::fprintf(stderr, "calibrate: no pen: %s\n", io->pen->statusMessage().c_str());
      return 1;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, io->display->framebuffer());
    glViewport(0, 0, io->w, io->h);
    Painter(io->w, io->h).clear(0.25f, 0.05f, 0.05f);  // dark red: waiting for the pen
    io->say({"Waiting for the pen", "Connect the tablet and bring the pen near it.",
             io->pen->statusMessage(), "Esc quits."},
            0.35f);
    io->display->present(&error);
    io->pen->poll(50, ignored);
    for (const DisplayEvent& e : io->display->pollEvents())
      if (commandFor(e) == Command::kQuit) return 1;
  }
  return 0;
}

// --pressure: light press, firm press, [pressure_range] for the session.
int runPressure(const Args& args, const Settings& s) {
  const double timeout_s = std::atof(args.get("timeout", "300").c_str());
  InteractiveIo io;
  if (int rc = openInteractive(args, timeout_s, &io)) return rc;
  const PenDeviceInfo device = io.pen->deviceInfo();
  if (device.pressure_max <= 0) {
    std::fprintf(stderr, "calibrate: this pen reports no pressure\n");
    return 1;
  }
  const CalibrationProfile profile = baseProfile(device, 0, s);
  NibOffsetDetector nib(profile.pressure.nib);
  // The presses are journalled too; the result goes in as the session's record.
  JournalWriter journal;
  if (auto record = args.get("record")) {
    if (!journal.open(*record)) {
      std::fprintf(stderr, "calibrate: %s (continuing without a record)\n",
                   journal.error().c_str());
    }
  }
  const std::vector<uint8_t> dev_bytes = encodeDeviceInfo(device);
  journal.append(JournalRecordType::kDevice, 0, dev_bytes.data(), dev_bytes.size());
  PressureRangeCollector collector(profile.pressure.contact.down, 100,
                                   profile.pressure.light_target);
  const auto start = std::chrono::steady_clock::now();
  std::vector<PenSample> samples;
  std::string error;
  bool was_in_proximity = false;
  auto step = collector.step();
  std::printf("press lightly and hold (0.5 s), then lift\n");
  for (;;) {
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >
        timeout_s) {
      std::fprintf(stderr, "calibrate: timed out after %.0f s\n", timeout_s);
      return 1;
    }
    for (const DisplayEvent& e : io.display->pollEvents())
      if (commandFor(e) == Command::kQuit) return 1;
    samples.clear();
    io.pen->poll(5, samples);
    if (io.pen->connection() == PenConnection::kFinished && samples.empty()) {
      std::fprintf(stderr, "calibrate: the replay ended before both presses\n");
      return 1;
    }
    for (const PenSample& sample : samples) {
      journal.appendPenSample(sample);
      if (sample.in_proximity && !was_in_proximity) nib.proximityIn();
      was_in_proximity = sample.in_proximity;
      nib.observe(sample, device.distance_max > 0);
      collector.feed(sample.in_proximity ? nib.correct(sample.pressure) : 0.0f);
      if (collector.step() == step) continue;
      step = collector.step();
      if (step == PressureRangeCollector::Step::kFirm) {
        std::printf("now press firmly and hold (0.5 s), then lift\n");
        continue;
      }
      const PressureRangeFit& fit = collector.result();
      if (!fit.range) {
        std::printf("%s; again: press lightly and hold, then lift\n", fit.error.c_str());
        collector.restart();
        step = collector.step();
        continue;
      }
      const std::string text = pressureRangeToToml(*fit.range);
      journal.append(JournalRecordType::kSession, sample.t_ns, text);
      std::printf("light press %.3f, firm press %.3f (nib offset %.3f)\n%s", fit.light, fit.firm,
                  nib.offset(), text.c_str());
      if (auto path = args.get("session-out")) {
        std::ofstream out(*path, std::ios::binary | std::ios::trunc);
        out << text;
        if (!out) {
          std::fprintf(stderr, "calibrate: %s: cannot be written\n", path->c_str());
          return 1;
        }
      }
      return 0;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, io.display->framebuffer());
    glViewport(0, 0, io.w, io.h);
    Painter p(io.w, io.h);
    p.clear(0.08f, 0.09f, 0.11f);
    const bool light = collector.step() == PressureRangeCollector::Step::kLight;
    // A pale box asks for a light press, a deep one for a firm press; the bar fills as the
    // press is held.
    p.rect(io.w * 0.3, io.h * 0.3, io.w * 0.4, io.h * 0.4, light ? 0.6f : 0.1f,
           light ? 0.75f : 0.2f, light ? 0.95f : 0.6f);
    const double held = std::min(
        1.0, static_cast<double>(collector.held()) / static_cast<double>(collector.holdSamples()));
    p.rect(io.w * 0.3, io.h * 0.75, io.w * 0.4 * held, 12, 0.3f, 0.8f, 0.3f);
    io.say({light ? "Press lightly, as gently as you would paint" : "Now press firmly",
            "Hold the pen still until the green bar is full, then lift it.", "Esc quits."});
    if (!io.display->present(&error)) {
      std::fprintf(stderr, "calibrate: %s\n", error.c_str());
      return 2;
    }
  }
}

int runInteractive(const Args& args, const Settings& s) {
  const double timeout_s = std::atof(args.get("timeout", "300").c_str());
  InteractiveIo io;
  if (int rc = openInteractive(args, timeout_s, &io)) return rc;
  PenSource* pen = io.pen.get();
  Display* display = io.display.get();
  const int w = io.w, h = io.h;
  std::string error;
  const bool auto_accept = args.has("yes");
  std::string snapshot = args.get("snapshot", "");  // PNG of the first result screen
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  std::vector<PenSample> samples;
  const PenDeviceInfo device = pen->deviceInfo();
  const bool uses_pressure = device.pressure_max > 0;
  const CalibrationProfile base = baseProfile(device, 0, s);
  const double w_mm = device.x_res > 0 ? device.x_max / device.x_res : 0.0;
  const double h_mm = device.y_res > 0 ? device.y_max / device.y_res : 0.0;
  const AreaMapping area = computeAreaMapping(base.area, w_mm, h_mm, w, h);
  if (!area.ok) {
    std::fprintf(stderr, "calibrate: %s\n", area.error.c_str());
    return 2;
  }

  JournalWriter journal;
  const std::string record = args.get("record", defaultRecordPath(s.state_dir));
  if (!journal.open(record)) {
    std::fprintf(stderr, "calibrate: %s (continuing without a record)\n", journal.error().c_str());
  } else {
    std::printf("recording %s\n", record.c_str());
  }
  int64_t last_t = 0;
  const std::vector<uint8_t> dev_bytes = encodeDeviceInfo(device);
  journal.append(JournalRecordType::kDevice, 0, dev_bytes.data(), dev_bytes.size());
  journal.append(JournalRecordType::kMarker, 0, screenMarker(w, h));
  const std::vector<glm::dvec2> targets = targetLayout(s.targets, w, h);
  for (size_t i = 0; i < targets.size(); ++i) {
    journal.append(JournalRecordType::kMarker, 0, targetMarker(i, targets[i]));
  }

  // Between the middle and bottom rows of targets, clear of their labels.
  const Button accept{w * 0.3 - 90, h * 0.7 - 50, 180, 100};
  const Button redo{w * 0.7 - 90, h * 0.7 - 50, 180, 100};
  TapCollector collector;
  std::vector<Tap> taps;
  std::optional<CalibrationFit> fit;
  uint64_t serial = 0;
  glm::dvec2 cursor(-100.0);
  bool in_contact_on_result = false;

  for (;;) {
    if (elapsed() > timeout_s) {
      std::fprintf(stderr, "calibrate: timed out after %.0f s\n", timeout_s);
      return 1;
    }
    for (const DisplayEvent& e : display->pollEvents()) {
      if (commandFor(e) == Command::kQuit) {
        std::printf("left without saving\n");
        return 1;
      }
      if (commandFor(e) == Command::kSpace && fit && fit->ok) {
        journal.append(JournalRecordType::kCalibration, last_t,
                       formatCalibrationProfile(fit->profile));
        return saveFit(*fit, s, nullptr);
      }
    }
    samples.clear();
    pen->poll(fit ? 10 : 5, samples);
    if (pen->connection() == PenConnection::kFinished && samples.empty()) {
      std::fprintf(stderr, "calibrate: the replay ended with %zu of %zu taps\n", taps.size(),
                   targets.size());
      return 1;
    }
    for (const PenSample& sample : samples) {
      journal.appendPenSample(sample);
      last_t = sample.t_ns;
      if (sample.tool_serial) serial = sample.tool_serial;
      if (sample.in_proximity)
        cursor = applyTransform(area.tablet_to_screen, {sample.x_mm, sample.y_mm});
      if (!fit) {
        const bool was_in_contact = collector.inContact();
        std::optional<glm::dvec2> tap = collector.feed(sample, uses_pressure);
        if (!tap) {
          if (was_in_contact && !collector.inContact()) {
            std::printf("target %zu: %s\n", taps.size(), collector.lastRejection().c_str());
          }
          continue;
        }
        taps.push_back({targets[taps.size()], *tap});
        std::printf("target %zu: tap at (%.2f, %.2f) mm\n", taps.size() - 1, tap->x, tap->y);
        if (taps.size() == targets.size()) {
          const uint64_t tool = s.per_tool ? serial : 0;
          fit = fitCalibration(base, device, tool, w, h, taps, s.fit);
          if (!fit->ok) {
            std::fprintf(stderr, "calibrate: %s; tap the targets again\n", fit->error.c_str());
            journal.append(JournalRecordType::kMarker, last_t, "calibrate redo");
            taps.clear();
            fit.reset();
            continue;
          }
          printFit(*fit, taps);
          if (auto_accept) break;  // after drawing the result screen once
          std::printf("tap the green box (or press Space) to accept, the orange box to redo\n");
        }
      } else {
        // Result screen: a tap (contact then lift) inside a box chooses it.
        const bool down =
            uses_pressure ? sample.pressure >= base.pressure.contact.down : sample.tipDown();
        if (down) in_contact_on_result = true;
        if (!down && in_contact_on_result) {
          in_contact_on_result = false;
          if (accept.contains(cursor)) {
            journal.append(JournalRecordType::kCalibration, last_t,
                           formatCalibrationProfile(fit->profile));
            return saveFit(*fit, s, nullptr);
          }
          if (redo.contains(cursor)) {
            std::printf("redo\n");
            journal.append(JournalRecordType::kMarker, last_t, "calibrate redo");
            taps.clear();
            fit.reset();
            collector = TapCollector();
          }
        }
      }
    }

    // Draw the frame.
    glBindFramebuffer(GL_FRAMEBUFFER, display->framebuffer());
    glViewport(0, 0, w, h);
    Painter p(w, h);
    p.clear(0.08f, 0.09f, 0.11f);
    std::vector<UiLabel> labels;
    const float size = std::max(18.0f, float(h) / 30.0f);
    if (!fit) {
      p.rect(0, 0, w * static_cast<double>(taps.size()) / targets.size(), 6, 0.3f, 0.7f, 0.3f);
      for (size_t i = 0; i < taps.size(); ++i) p.crosshair(targets[i], 8, 0.3f, 0.6f, 0.3f);
      const glm::dvec2 t = targets[taps.size()];
      p.crosshair(t, 30, 1.0f, 1.0f, 1.0f);
      p.rect(t.x - 3, t.y - 3, 7, 7, collector.inContact() ? 0.2f : 1.0f, 0.3f, 0.2f);
      char line[96];
      std::snprintf(line, sizeof line, "Tap the centre of the cross with the pen (%zu of %zu)",
                    taps.size() + 1, targets.size());
      labels.push_back(
          {float(w) * 0.5f, float(h) * 0.5f + size * 2.5f, line, size, 0xffffffffu, true});
    } else {
      for (size_t i = 0; i < taps.size(); ++i) {
        const glm::dvec2 mapped = applyTransform(
            fit->profile.correction, applyTransform(area.tablet_to_screen, taps[i].pen_mm));
        p.crosshair(taps[i].target_px, 12, 0.8f, 0.8f, 0.8f);
        p.rect(mapped.x - 3, mapped.y - 3, 7, 7, 1.0f, 0.3f, 0.2f);
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.1f px", fit->fit.residuals[i]);
        labels.push_back({float(taps[i].target_px.x) + 16.0f, float(taps[i].target_px.y) + 16.0f,
                          buf, size * 0.8f, 0xffffffffu, false});
      }
      char buf[96];
      std::snprintf(buf, sizeof buf, "Largest error %.2f px", fit->fit.max_residual);
      labels.push_back(
          {float(w) * 0.5f, float(h) * 0.3f - 1.5f * size, buf, size * 1.3f, 0xffff99ffu, true});
      p.rect(accept.x, accept.y, accept.w, accept.h, 0.2f, 0.65f, 0.25f);
      p.rect(redo.x, redo.y, redo.w, redo.h, 0.9f, 0.5f, 0.1f);
      labels.push_back({float(accept.x + accept.w * 0.5), float(accept.y + accept.h + 0.4 * size),
                        "Accept (Space)", size, 0xffffffffu, true});
      labels.push_back({float(redo.x + redo.w * 0.5), float(redo.y + redo.h + 0.4 * size), "Redo",
                        size, 0xffffffffu, true});
    }
    p.rect(cursor.x - 2, cursor.y - 2, 5, 5, 0.9f, 0.9f, 1.0f);
    io.ui.drawLabels(w, h, labels);
    if (fit && !snapshot.empty()) {
      try {
        writePng(snapshot, readFramebufferRgba8(display->framebuffer(), w, h));
        std::printf("wrote %s\n", snapshot.c_str());
      } catch (const ImageIoError& e) {
        std::fprintf(stderr, "calibrate: %s\n", e.what());
      }
      snapshot.clear();
    }
    if (!display->present(&error)) {
      std::fprintf(stderr, "calibrate: %s\n", error.c_str());
      return 2;
    }
    if (fit && auto_accept) {
      journal.append(JournalRecordType::kCalibration, last_t,
                     formatCalibrationProfile(fit->profile));
      return saveFit(*fit, s, nullptr);
    }
  }
}

}  // namespace

int commandCalibrate(int argc, char** argv) {
  Args args(argc, argv, {"help", "yes", "save", "per-tool", "pressure"});
  if (args.has("help")) return usage(0);
  const std::vector<std::string> known = {
      "help",    "yes",        "save",      "per-tool", "targets",     "fit",
      "backend", "device",     "display",   "record",   "timeout",     "points",
      "journal", "config-dir", "state-dir", "pressure", "session-out", "snapshot"};
  if (auto bad = args.unknown(known); !bad.empty()) {
    std::fprintf(stderr, "calibrate: unknown option %s\n", bad[0].c_str());
    return usage(2);
  }
  Settings s;
  s.targets = static_cast<int>(args.getInt("targets", 9));
  if (s.targets != 5 && s.targets != 9) {
    std::fprintf(stderr, "calibrate: --targets must be 5 or 9\n");
    return 2;
  }
  if (!parsePointFitKind(args.get("fit", "homography"), &s.fit) || s.fit == PointFitKind::kNone) {
    std::fprintf(stderr, "calibrate: --fit must be homography or affine\n");
    return 2;
  }
  if (!args.error().empty()) {
    std::fprintf(stderr, "calibrate: %s\n", args.error().c_str());
    return 2;
  }
  s.per_tool = args.has("per-tool");
  s.config_dir = args.get("config-dir", defaultConfigDir());
  s.state_dir = args.has("state-dir") ? args.get("state-dir", "") : stateDir();

  if (args.has("pressure")) return runPressure(args, s);
  if (auto path = args.get("points")) return runPointsFile(*path, s, args.has("save"));
  if (auto path = args.get("journal")) return runJournal(*path, s, args.has("save"));
  return runInteractive(args, s);
}

}  // namespace cb
