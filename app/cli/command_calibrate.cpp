// `cloudbrush calibrate`: the pen-driven N-point calibration.
//
// Interactive (default): the calibration screens (app/shell/calibrate/calibrate_flow_screen.h) on
// the shell's one frame loop: wait for the pen, tap the targets one at a time (corners and centre,
// or a 3x3 grid), see the residual of every point in pixels; tapping the green box (or Space)
// accepts and saves the profile for this tablet under the state directory, the orange box
// redoes, Esc leaves without saving. The whole session is recorded as a journal (device, screen,
// targets as markers, raw pen samples, the accepted profile), so it can be re-fitted.
//
// Non-interactive: --points FILE fits a tap file (calibration/n_point_calibration.h);
// --journal FILE re-fits a recorded calibration session. Both print the fit and, with --save,
// write the profile.
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/core/atomic_file.h"
#include "app/core/config_paths.h"
#include "app/render/gl/display.h"
#include "app/render/image_io.h"
#include "app/shell/calibrate/calibrate_flow_screen.h"
#include "app/shell/calibrate/calibrate_pen_input.h"
#include "app/shell/frame_loop.h"
#include "calibration/n_point_calibration.h"
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

void logLine(const std::string& line) {
  std::printf("%s\n", line.c_str());
}

CalibrationProfile baseProfile(const PenDeviceInfo& device, uint64_t serial, const Settings& s) {
  return calibrationBaseProfile(device, serial, s.config_dir, s.state_dir,
                                [](const std::string& m) {
                                  if (m.rfind("area mapping from ", 0) == 0)
                                    logLine(m);
                                  else
                                    std::fprintf(stderr, "calibrate: %s\n", m.c_str());
                                });
}

void printFit(const CalibrationFit& fit, const std::vector<Tap>& taps) {
  logLine(describeFit(fit, taps));
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

// --journal FILE: device, screen and targets from the records, taps from the raw samples.
int runJournal(const std::string& path, const Settings& s, bool save) {
  JournalReadResult j = readJournal(path);
  if (!j.error.empty()) std::fprintf(stderr, "calibrate: %s\n", j.error.c_str());
  std::optional<PenDeviceInfo> device;
  int w = 0, h = 0;
  std::vector<glm::dvec2> targets;
  std::vector<Tap> taps;
  // The same path as on screen: calibrated samples, pen events, taps from down to up.
  CalibratePenInput input;
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
        if (device && w > 0 && h > 0 && w <= 65536 && h <= 65536)
          input.start(baseProfile(*device, 0, s), *device, w, h);
      } else if (what == "target") {
        size_t i = 0;
        glm::dvec2 t;
        if (in >> i >> t.x >> t.y && i == targets.size()) targets.push_back(t);
      } else if (what == "redo") {
        taps.clear();
      }
    } else if (r.type == JournalRecordType::kPenSample && input.started()) {
      std::optional<PenSample> sample = decodePenSample(r.payload);
      if (!sample) continue;
      if (sample->tool_serial) serial = sample->tool_serial;
      input.feed({*sample}, [&](const CalibratePenEvent& e) {
        if (auto tap = collectTap(collector, e))
          if (taps.size() < targets.size()) taps.push_back({targets[taps.size()], *tap});
      });
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

std::string defaultRecordPath(const std::string& state_dir) {
  char stamp[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::gmtime(&now));
  return (std::filesystem::path(state_dir) / (std::string("calibration-") + stamp + ".cbj"))
      .string();
}

// How the calibration ended, said, as the exit status: 0 saved (or the pressure range shown,
// and written to --session-out), 1 left, timed out, cancelled or failed.
int calibrationOutcome(const Args& args, const std::optional<CalibrateOutcome>& outcome,
                       const FrameLoopResult& result, double timeout_s) {
  if (!outcome) {
    if (result.quit_reason == "time limit") {
      std::fprintf(stderr, "calibrate: timed out after %.0f s\n", timeout_s);
    } else {
      std::printf("left without saving (%s)\n", result.quit_reason.c_str());
    }
    return 1;
  }
  switch (outcome->kind) {
    case CalibrateOutcome::Kind::kSaved:
      return 0;
    case CalibrateOutcome::Kind::kPressureRange:
      std::printf("%s", outcome->message.c_str());
      if (auto path = args.get("session-out")) {
        std::string error;
        if (!writeFileAtomically(*path, outcome->message, &error)) {
          std::fprintf(stderr, "calibrate: %s: cannot be written: %s\n", path->c_str(),
                       error.c_str());
          return 1;
        }
      }
      return 0;
    case CalibrateOutcome::Kind::kCancelled:
      std::printf("%s\n", outcome->message.c_str());
      return 1;
    case CalibrateOutcome::Kind::kFailed:
      break;
  }
  std::fprintf(stderr, "calibrate: %s\n", outcome->message.c_str());
  return 1;
}

// The interactive calibration (taps, or --pressure): the pen and the display opened, the
// calibration screens run on the frame loop until they are done, Esc, or the timeout.
int runInteractive(const Args& args, const Settings& s, bool pressure) {
  const double timeout_s = std::atof(args.get("timeout", "300").c_str());
  PenSourceOptions po;
  po.backend = args.get("backend", "auto");
  po.device = args.get("device", "");
  po.realtime = false;  // replays are fed as fast as the loop takes them
  po.device_dir = configFile("devices");
  std::string error;
  std::unique_ptr<PenSource> pen = openPenSource(po, &error);
  if (!pen) {
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
  std::unique_ptr<Display> display = openDisplay(dopt, &error, &note);
  if (!display) {
    std::fprintf(stderr, "calibrate: no display: %s\n", error.c_str());
    return 2;
  }
  if (!note.empty()) std::printf("display: %s\n", note.c_str());
  if (!display->makeCurrent(&error)) {
    std::fprintf(stderr, "calibrate: %s\n", error.c_str());
    return 2;
  }
  const int w = display->width(), h = display->height();
  std::printf("display %s %dx%d, pen backend %s\n", display->platformName(), w, h,
              pen->backendName());
  if (pen->connection() != PenConnection::kConnected)
    std::fprintf(stderr,
                 "calibrate: waiting for the pen (%s): connect the tablet and bring the pen near "
                 "it; Esc quits\n",
                 pen->statusMessage().c_str());

  // The session's record: always for the taps (so they can be re-fitted), for the presses
  // only when asked for.
  JournalWriter journal;
  bool recording = false;
  const std::optional<std::string> record =
      pressure ? args.get("record")
               : std::optional<std::string>(args.get("record", defaultRecordPath(s.state_dir)));
  if (record) {
    recording = journal.open(*record);
    if (!recording)
      std::fprintf(stderr, "calibrate: %s (continuing without a record)\n",
                   journal.error().c_str());
    else if (!pressure)
      std::printf("recording %s\n", record->c_str());
  }

  CalibrateFlowOptions options;
  options.task =
      pressure ? CalibrateFlowOptions::Task::kPressure : CalibrateFlowOptions::Task::kTargets;
  options.targets = s.targets;
  options.fit = s.fit;
  options.per_tool = s.per_tool;
  options.auto_accept = args.has("yes");
  options.config_dir = s.config_dir;
  options.state_dir = s.state_dir;
  options.journal = recording ? &journal : nullptr;
  options.log = [](const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  };
  CalibrateFlowScreen flow(pen.get(), w, h, options);

  FrameLoopOptions loop_options;
  loop_options.max_seconds = timeout_s;
  std::string snapshot = args.get("snapshot", "");  // PNG of the first result screen
  loop_options.after_draw = [&](const FrameContext& frame) {
    if (snapshot.empty() || flow.stage() != CalibrateFlowScreen::Stage::kResult) return;
    try {
      writePng(snapshot,
               readFramebufferRgba8(frame.display.framebuffer(), frame.width, frame.height));
      std::printf("wrote %s\n", snapshot.c_str());
    } catch (const ImageIoError& e) {
      std::fprintf(stderr, "calibrate: %s\n", e.what());
    }
    snapshot.clear();
  };
  FrameLoop loop(*display, pen.get());
  FrameLoopResult result;
  if (!loop.run(flow, loop_options, &result, &error)) {
    std::fprintf(stderr, "calibrate: %s\n", error.c_str());
    return 2;
  }
  return calibrationOutcome(args, flow.outcome(), result, timeout_s);
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

  if (auto path = args.get("points")) return runPointsFile(*path, s, args.has("save"));
  if (auto path = args.get("journal")) return runJournal(*path, s, args.has("save"));
  return runInteractive(args, s, args.has("pressure"));
}

}  // namespace cb
