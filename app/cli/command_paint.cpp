// `cloudbrush` / `cloudbrush paint`: the main job. On a display (KMS or X11, fullscreen) the
// painter: the pen (drivers/, any backend) through calibration, brush and mapping into the volume
// (PaintSession, journalled to the state dir), shown by PaintLoop; without a tablet the bundled
// cloud orbits and the missing tablet is shown as a state. With no display (surfaceless) and no
// pen backend named: a headless render of the bundled cloud to PNG + EXR.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/cli/args.h"
#include "app/cli/command_kiosk.h"
#include "app/cli/commands.h"
#include "app/cli/paint_headless.h"
#include "app/core/config_override.h"
#include "app/core/config_paths.h"
#include "app/kiosk/data_dir_check.h"
#include "app/kiosk/kiosk_config.h"
#include "app/kiosk/kiosk_heap.h"
#include "app/kiosk/kiosk_service.h"
#include "app/kiosk/kiosk_texts.h"
#include "app/kiosk/watchdog_interval.h"
#include "app/mapping/mapping_config.h"
#include "app/render/gl/display.h"
#include "app/render/render_config.h"
#include "app/render/volume_renderer.h"
#include "app/session/paint_session.h"
#include "app/session/session_replay.h"
#include "app/session/session_resume.h"
#include "app/shell/keymap.h"
#include "app/shell/kiosk/attract_journal.h"
#include "app/shell/kiosk/kiosk_screen.h"
#include "app/shell/painter/paint_loop.h"
#include "app/shell/painter/paint_screen.h"
#include "app/volume/scene_generators.h"
#include "app/volume/sky_extent.h"
#include "app/volume/volume_file.h"
#include "drivers/open_pen_source.h"
#include "drivers/replay/replay_pen_source.h"

namespace cb {
namespace {

constexpr const char* kUsage =
    "usage: cloudbrush [paint] [OPTIONS]\n"
    "\n"
    "The painter. On a display it opens fullscreen at the paint view with a hint until the\n"
    "first stroke: press and drag (the pen, or the mouse when no tablet is connected) and the\n"
    "footprint shows live; when the pen lifts the stroke becomes a lit cloud. The session is\n"
    "journalled (its path is printed) for `cloudbrush replay`. With --backend none the bundled\n"
    "cloud orbits. With no display and no --backend it renders the bundled cloud headlessly and\n"
    "writes a PNG and an EXR, printing their paths.\n"
    "\n"
    "options:\n"
    "  --display auto|kms|x11|surfaceless\n"
    "                      where to draw (auto: KMS if it can take the display, else X11 if\n"
    "                      DISPLAY is set, else surfaceless = headless render)\n"
    "  --drm-device PATH   DRM card for kms (default: the first with a connected connector)\n"
    "  --size WxH          headless image size (default 1280x720)\n"
    "  --out-dir DIR       headless output directory (default ./out)\n"
    "  --grid N            voxels across the home box, N³ (default 256)\n"
    "  --sky-span N        home boxes across the sky in x and z at the start (default 4: a\n"
    "                      1024x256x1024 sky for grid 256; 1 = the thesis's one box)\n"
    "  --sky-max-span N    the sky grows with what is painted, up to N home boxes across\n"
    "                      (default 8, as far as 2048 voxels allow; = --sky-span: fixed)\n"
    "  --seed N            seed of the bundled cloud (default 1)\n"
    "  --orbit DEG         orbit speed in degrees per second (default 6; 0 = still)\n"
    "  --moving-scale F    starting resolution scale while the camera moves (default 0.5;\n"
    "                      adapted towards 20 fps)\n"
    "  --frames N          on a display, quit after N frames (default: run until Esc)\n"
    "  --seconds S         on a display, quit after S seconds (scripted runs)\n"
    "  --stats             print ray-sample statistics of full-resolution frames\n"
    "  --keys LETTERS      press these keys at the start, in order (scripted runs): s, c, b, m\n"
    "  --backend NAME      pen: auto (default), evdev, hidraw, libusb, replay or none\n"
    "  --pen-device PATH   pen device node / hidraw path (default: discover)\n"
    "  --journal FILE      with --backend replay: the session journal to play as the pen\n"
    "  --session-dir DIR   where session journals go (default <state dir>/sessions)\n"
    "  --no-record         do not journal this session\n"
    "  --sync-udp [HOST:]PORT\n"
    "                      send task and stroke boundaries as UDP datagrams (JOURNAL.md, Sync\n"
    "                      records; default host 127.0.0.1; off by default; not in the kiosk)\n"
    "  --resume FILE       journal the session to FILE; when FILE already holds a session (the\n"
    "                      painter crashed or was stopped), replay it to rebuild the cloud, the\n"
    "                      history and the settings, and carry on after its last whole record\n"
    "                      (with --backend replay, the pen continues after the last sample FILE\n"
    "                      holds)\n"
    "  --open FILE         start from a saved cloud (a .vol of the session's grid)\n"
    "  --kiosk             exhibition mode (what `cloudbrush kiosk` runs; settings in\n"
    "                      config/kiosk.toml): the attract loop replays a journal until a pen\n"
    "                      comes near, visitor mode (no quit keys, no operator commands), idle\n"
    "                      countdown and reset, the operator panel (key combination + PIN), the\n"
    "                      gallery, \"reconnect the pen\", systemd notifications and watchdog\n"
    "                      pings, health.json; everything it writes goes into --data-dir\n"
    "  --idle-seconds S    kiosk: clear the sky after S s without input (kiosk.toml: 90)\n"
    "  --warning-seconds S kiosk: the countdown shown before that (kiosk.toml: 10)\n"
    "  --language CODE     kiosk: visitor texts (kiosk/texts.toml: en, zh; kiosk.toml: en)\n"
    "  --gallery on|off    kiosk: keep each visitor's cloud (kiosk.toml [gallery] enabled)\n"
    "  --data-dir DIR      kiosk: sessions, gallery, exports, operator.log, health.json\n"
    "                      (default the state dir)\n"
    "  --metrics-dir DIR   kiosk: write cloudbrush.prom there for node_exporter's textfile\n"
    "                      collector (kiosk.toml [monitoring] metrics_dir; default none)\n"
    "  --set-pin           (`cloudbrush kiosk` only, with --data-dir at most) set the operator\n"
    "                      PIN from stdin (4-12 digits; kept hashed in the data dir; no default)\n"
    "  --make-attract-journal FILE\n"
    "                      (`cloudbrush kiosk` only, alone) write the bundled attract journal\n"
    "  --place FILE        make a cloud from a picture (.png) or a model (.obj, .ply, .gltf)\n"
    "                      at the canvas, seen from the starting view\n"
    "  --morph-to FILE     F morphs the cloud into this saved cloud (default: the newest saved\n"
    "                      cloud of the state dir, else the bundled cumulus)\n"
    "  --morph-seconds S   how long the morph plays (default 5)\n"
    "  --help              this text\n"
    "\n"
    "keys (H or ? shows them on screen; mode keys act only in their mode):\n"
    "  every mode  1-5 modes (camera, canvas, paint, erase, light), M the menu, B the brush\n"
    "              (2d/3d/skeleton), N the mapping (hybrid/ray-marching/sheet), T the style,\n"
    "              G a good view, C the last stroke's circles, S details (statistics),\n"
    "              Ctrl+Z/Ctrl+Y undo/redo, Delete clears (Ctrl+Z brings it back), Ctrl+S saves\n"
    "              (cloud-DATE_TIME.vol in the state dir), Ctrl+O opens the last saved,\n"
    "              Esc/q quits (with unsaved work: asks; Esc again or Y quits)\n"
    "  1 camera    R reset, arrows top/front/left/3-4 views, Shift+arrows pan, P drag pans,\n"
    "              -/+ zoom, Space auto-rotation\n"
    "  2 canvas    PgUp/PgDn one voxel, -/+ thickness\n"
    "  4 erase     V vacuum/rub-out, -/+ size, Space cuts (vacuum)\n"
    "  5 light     -/+ warmer/cooler\n"
    "B, N and T apply from the next stroke and are journalled. While the pen is in range the\n"
    "screen outside where a stroke can land is veiled; ink there is left out, and the screen says so.\n";

std::atomic<bool> g_stop{false};
void onSignal(int) {
  g_stop.store(true);
}

bool parseSize(const std::string& text, int* w, int* h) {
  int consumed = 0;
  return std::sscanf(text.c_str(), "%dx%d%n", w, h, &consumed) == 2 &&
         consumed == int(text.size()) && *w > 0 && *h > 0 && *w <= 16384 && *h <= 16384;
}

int fail(const std::string& message, int code = 1) {
  std::fprintf(stderr, "cloudbrush paint: %s\n", message.c_str());
  return code;
}

// The painter's command line, checked (parsePaintArgs).
struct PaintArgs {
  DisplayOptions display_options;
  long grid = 256, sky_span = kDefaultSkySpan, sky_max_span = kMaxSkySpan, seed = 1;
  SkyExtent sky;
  PaintLoopOptions loop_options;
  bool kiosk = false;
  KioskConfig kiosk_config;
  // Kiosk: the first bad config file or unusable data dir. Shown on the screen (and logged)
  // instead of exiting into a restart loop (app/shell/kiosk/kiosk_error_screen.h); every config
  // file alike. The painter exits with the message.
  std::string kiosk_problem;
  std::string backend, resume_path;
};

// Reads and checks the options into *p: -1 when they hold, else the exit status (said on
// stderr).
int parsePaintArgs(Args& args, PaintArgs* p) {
  std::string error;
  DisplayOptions& display_options = p->display_options;
  long &grid = p->grid, &sky_span = p->sky_span, &sky_max_span = p->sky_max_span, &seed = p->seed;
  SkyExtent& sky = p->sky;
  PaintLoopOptions& loop_options = p->loop_options;
  bool& kiosk = p->kiosk;
  KioskConfig& kiosk_config = p->kiosk_config;
  std::string& kiosk_problem = p->kiosk_problem;
  std::string &backend = p->backend, &resume_path = p->resume_path;
  const std::string platform = args.get("display", "auto");
  if (!parseDisplayPlatform(platform, &display_options.platform))
    return fail("--display: expected auto, kms, x11 or surfaceless, got '" + platform + "'", 2);
  display_options.drm_device = args.get("drm-device", "");
  display_options.lock_vt = args.has("kiosk");  // no VT switching out of the kiosk
  const std::string size = args.get("size", "1280x720");
  if (!parseSize(size, &display_options.width, &display_options.height))
    return fail("--size: expected WxH (1..16384 each), got '" + size + "'", 2);
  grid = args.getInt("grid", 256);
  sky_span = args.getInt("sky-span", kDefaultSkySpan);
  sky = SkyExtent{int(grid), int(sky_span)};
  sky_max_span = args.getInt("sky-max-span", std::max(long(kMaxSkySpan), sky_span));
  seed = args.getInt("seed", 1);
  loop_options.orbit_degrees_per_second = float(args.getDouble("orbit", 6.0));
  loop_options.moving_scale = float(args.getDouble("moving-scale", 0.5));
  loop_options.max_frames = args.getInt("frames", 0);
  loop_options.max_seconds = args.getDouble("seconds", 0.0);
  loop_options.print_stats = args.has("stats");
  loop_options.morph_target = args.get("morph-to", "");
  loop_options.morph_seconds = args.getDouble("morph-seconds", 5.0);
  if (!(loop_options.morph_seconds > 0.0 && loop_options.morph_seconds <= 3600.0))
    return fail("--morph-seconds: expected a time in (0, 3600] seconds", 2);
  kiosk = args.has("kiosk");
  if (kiosk) {
    try {
      std::error_code ec;
      if (std::filesystem::exists(configFile("kiosk.toml"), ec))
        kiosk_config = loadKioskConfig(configFile("kiosk.toml"));
      else if (ec)
        kiosk_problem = configFile("kiosk.toml") + ": " + ec.message();
      // The administrator's /etc/cloudbrush/kiosk.toml, key by key over the shipped one.
      if (const std::string local = configOverrideFile("kiosk.toml"); !local.empty())
        kiosk_config = loadKioskConfig(local, kiosk_config);
    } catch (const std::exception& e) {
      kiosk_problem = e.what();
    }
    loop_options.visitor_mode = true;
    kiosk_config.idle_seconds = args.getDouble("idle-seconds", kiosk_config.idle_seconds);
    kiosk_config.warning_seconds = args.getDouble("warning-seconds", kiosk_config.warning_seconds);
    kiosk_config.language = args.get("language", kiosk_config.language);
    kiosk_config.metrics_dir = args.get("metrics-dir", kiosk_config.metrics_dir);
    if (args.has("orbit"))
      kiosk_config.orbit_degrees_per_second = loop_options.orbit_degrees_per_second;
    if (args.has("gallery")) {
      const std::string gallery = args.get("gallery", "");
      if (gallery != "on" && gallery != "off")
        return fail("--gallery: expected on or off, got '" + gallery + "'", 2);
      kiosk_config.gallery_enabled = gallery == "on";
    }
    if (kiosk_config.idle_seconds <= 0.0 || kiosk_config.warning_seconds < 0.0)
      return fail("--idle-seconds / --warning-seconds: expected positive seconds", 2);
  } else if (args.has("language") || args.has("gallery") || args.has("idle-seconds")) {
    return fail("--idle-seconds, --language and --gallery are kiosk options (--kiosk)", 2);
  }
  if (!args.error().empty()) return fail(args.error(), 2);
  if (grid < 8 || grid > 1024)
    return fail("--grid: expected 8..1024, got " + std::to_string(grid), 2);
  if (const std::string problem = sky.check(); !problem.empty())
    return fail("--sky-span: " + problem, 2);
  if (sky_max_span < sky_span || sky_max_span > kMaxSkySpan)
    return fail("--sky-max-span: expected " + std::to_string(sky_span) + ".." +
                    std::to_string(kMaxSkySpan) + " (at least --sky-span), got " +
                    std::to_string(sky_max_span),
                2);
  if (seed < 0) return fail("--seed: expected a non-negative integer", 2);
  if (loop_options.moving_scale <= 0.0f || loop_options.moving_scale > 1.0f)
    return fail("--moving-scale: expected a number in (0, 1]", 2);
  if (loop_options.max_frames < 0) return fail("--frames: expected N >= 0", 2);
  if (args.has("keys") && !parseKeyList(args.get("keys", ""), &loop_options.initial_keys, &error))
    return fail("--keys: " + error, 2);

  backend = args.get("backend", "auto");
  if (backend != "none" && backend != "auto" && backend != "evdev" && backend != "hidraw" &&
      backend != "libusb" && backend != "replay")
    return fail(
        "--backend: expected auto, evdev, hidraw, libusb, replay or none, got '" + backend + "'",
        2);
  if (backend == "replay" && !args.has("journal"))
    return fail("--backend replay needs --journal FILE", 2);
  resume_path = args.get("resume", "");
  if (!resume_path.empty() && args.has("no-record"))
    return fail("--resume records into its file; it cannot go with --no-record", 2);
  return -1;
}

// What the run did, on stdout: frames, pen samples and strokes, the volume's checksum.
void printPaintSummary(const PaintLoopSummary& summary, Display& display_ref, const PenSource* pen,
                       const PaintSession* painted, long grid, bool resuming) {
  Display* display = &display_ref;
  std::printf(
      "cloudbrush: %ld frames in %.1f s on %s (%s); orbit median %.1f ms/frame at scale %.2f, "
      "present %.1f ms\n",
      summary.frames, summary.seconds, display->platformName(), summary.quit_reason.c_str(),
      summary.median_frame_ms, summary.final_moving_scale, summary.median_present_ms);
  if (pen && summary.pen_samples == 0)
    std::printf("cloudbrush: no pen samples arrived; nothing painted or recorded\n");
  if (pen && summary.pen_samples > 0)
    std::printf(
        "cloudbrush: %ld pen samples, %ld strokes mapped; pen-up -> first lit frame "
        "median %.1f ms (%zu strokes, %dx%d, grid %ld); painting median %.1f ms/frame over %ld "
        "frames\n",
        summary.pen_samples, summary.strokes_mapped, summary.median_pen_up_to_lit_ms(),
        summary.pen_up_to_lit_ms.size(), display->width(), display->height(), grid,
        summary.median_painting_frame_ms, summary.painting_frames);
  // (The kiosk's visitors each have a journal of their own; no one checksum stands for them.)
  if (painted && (summary.pen_samples > 0 || resuming))
    std::printf(
        "cloudbrush: volume checksum %016llx (cloudbrush replay of the journal gives the "
        "same)\n",
        static_cast<unsigned long long>(volumeChecksum(painted->volume())));
  if (const FrameTiming* last = display->frameTimings().last(); last && last->has_vblank)
    std::printf("cloudbrush: last page flip: vblank sequence %u at %.6f s (monotonic)\n",
                last->vblank_sequence, double(last->shown_ns) / 1e9);
}

// The kiosk's visitor texts and attract journal into *setup (false: the texts did not load).
bool loadKioskAssets(const KioskConfig& kiosk_config, KioskSetup* out, std::string* error) {
  KioskSetup& setup = *out;
  try {
    setup.texts = KioskTexts::load(configFile("kiosk/texts.toml"), kiosk_config.language,
                                   [](const std::string& line) {
                                     std::fprintf(stderr, "cloudbrush kiosk: %s\n", line.c_str());
                                   });
  } catch (const std::exception& e) {
    *error = e.what();
    return false;
  }
  const std::filesystem::path attract_path =
      std::filesystem::path(kiosk_config.attract_journal).is_absolute()
          ? std::filesystem::path(kiosk_config.attract_journal)
          : std::filesystem::path(defaultConfigDir()) / kiosk_config.attract_journal;
  JournalReadResult attract = readJournal(attract_path.string());
  if (!attract.error.empty())
    std::fprintf(stderr, "cloudbrush kiosk: attract journal: %s (%zu records play)\n",
                 attract.error.c_str(), attract.records.size());
  setup.attract_journal = std::move(attract.records);
  return true;
}

// --resume: what the resumed journal held (restarting on the same session resumes
// it from its journal).
void reportResumed(const std::string& resume_path, const ResumedSession& resumed) {
  if (!resumed.warning.empty())
    std::fprintf(stderr, "cloudbrush: resume: %s\n", resumed.warning.c_str());
  if (!resumed.resumed) return;
  std::printf(
      "resumed %s: %zu records, %zu pen samples, %u strokes; recording on after byte "
      "%llu\n",
      resume_path.c_str(), resumed.replay.records_applied, resumed.replay.pen_samples,
      resumed.replay.strokes_mapped,
      static_cast<unsigned long long>(std::filesystem::file_size(resume_path)));
  std::fflush(stdout);
}

// The session's journal: into the --resume file, else <session dir>/<UTC time>.cbj.
void startSessionJournal(PaintSession* session, JournalWriter* journal,
                         const std::string& resume_path, const std::string& session_dir) {
  if (!resume_path.empty()) {
    session->recordTo(journal, 0);  // a new session in the --resume file
    std::printf("journal: %s\n", resume_path.c_str());
    std::fflush(stdout);
    return;
  }
  std::error_code ec;
  std::filesystem::create_directories(session_dir, ec);
  char stamp[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(stamp, sizeof stamp, "%Y%m%dT%H%M%SZ", std::gmtime(&now));
  const std::string path = session_dir + "/" + stamp + ".cbj";
  if (ec || !journal->open(path)) {
    std::fprintf(stderr, "cloudbrush: NOT RECORDING: cannot write the session journal %s: %s\n",
                 path.c_str(), ec ? ec.message().c_str() : journal->error().c_str());
    return;
  }
  session->recordTo(journal, 0);
  std::printf("journal: %s\n", path.c_str());
  std::fflush(stdout);
}

// What the painter opens, in the order it opens them (and so closes them in reverse: the session
// before the pen, the display last).
struct PaintRun {
  PaintArgs parsed;
  std::unique_ptr<Display> display;
  bool headless = false;
  RenderConfig render_config;
  Light light;
  std::unique_ptr<PenSource> pen;
  std::unique_ptr<PaintSession> session;
  JournalWriter journal;
  MappingConfig mapping;
  PaintSessionSettings settings;
  BrushConfig brush;
  bool resuming = false;          // --resume found a session in its file
  int64_t resumed_after_ns = -1;  // the resumed journal's last pen sample
  SyncMarkerSender sync_sender;
  std::string data_dir, session_dir;
  bool record = true;
};

// The display (KMS, X11 or surfaceless), said on stderr; nullptr with *error when none opens.
std::unique_ptr<Display> openPaintDisplay(const Args& args, const PaintArgs& parsed,
                                          std::string* error) {
  // Mesa's shader cache goes into the kiosk's data dir with everything else it writes, unless the
  // environment names one (the unit does): Mesa reads MESA_SHADER_CACHE_DIR when the display's
  // context is made, and without it writes under the passwd entry's home (~/.cache), not $HOME.
  // Mesa makes only the last folder: the data dir is made here (checked later, as before).
  if (parsed.kiosk && !std::getenv("MESA_SHADER_CACHE_DIR")) {
    const std::string dir = args.has("data-dir") ? args.get("data-dir", "") : stateDir();
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    ::setenv("MESA_SHADER_CACHE_DIR", (dir + "/mesa-shader-cache").c_str(), 0);
  }
  std::string choice_note;
  std::unique_ptr<Display> display = openDisplay(parsed.display_options, error, &choice_note);
  if (!display) return nullptr;
  std::fprintf(stderr, "cloudbrush: %s display %dx%d, OpenGL %s on %s\n", display->platformName(),
               display->width(), display->height(), display->context().version.c_str(),
               display->context().renderer.c_str());
  if (!choice_note.empty())
    std::fprintf(stderr, "cloudbrush: chose %s because %s\n", display->platformName(),
                 choice_note.c_str());
  if (!display->context().device.empty())  // headless: which EGL device rendered
    std::fprintf(stderr, "cloudbrush: rendered by %s%s%s\n", display->context().describe().c_str(),
                 display->context().device_note.empty() ? "" : "; passed over: ",
                 display->context().device_note.c_str());
  return display;
}

// render.toml, the pen, and for a painting session mapping.toml, brush.toml and the session's
// settings: -1 when they hold, else the exit status (said on stderr). In the kiosk a bad config
// file becomes the kiosk's problem instead.
int openConfigsAndPen(Args& args, PaintRun* run) {
  std::string error;
  const bool kiosk = run->parsed.kiosk;
  std::string& kiosk_problem = run->parsed.kiosk_problem;
  PaintLoopOptions& loop_options = run->parsed.loop_options;
  const std::string& backend = run->parsed.backend;
  try {
    if (std::filesystem::exists(configFile("render.toml")))
      run->render_config = loadRenderConfig(configFile("render.toml"));
  } catch (const std::exception& e) {
    if (!kiosk) return fail(e.what());
    if (kiosk_problem.empty()) kiosk_problem = e.what();
  }
  run->light = run->render_config.light;
  loop_options.render = run->render_config.options;
  if (!args.has("moving-scale")) loop_options.moving_scale = run->render_config.moving_scale;
  if (!run->headless && backend != "none") {
    PenSourceOptions pen_options;
    pen_options.backend = backend;
    pen_options.device = backend == "replay" ? args.get("journal", "") : args.get("pen-device", "");
    pen_options.device_dir = configFile("devices");
    run->pen = openPenSource(pen_options, &error);
    if (!run->pen) return fail("--backend " + backend + ": " + error, 2);
  }
  if (!run->pen && !kiosk) return -1;  // a kiosk without a tablet still paints with a mouse
  try {
    if (std::filesystem::exists(configFile("mapping.toml")))
      run->mapping = loadMappingConfig(configFile("mapping.toml"));
  } catch (const std::exception& e) {
    if (!kiosk) return fail(e.what());
    if (kiosk_problem.empty()) kiosk_problem = e.what();
  }
  PaintSessionSettings& settings = run->settings;
  settings.screen_width = run->display->width();
  settings.screen_height = run->display->height();
  settings.grid = int(run->parsed.grid);
  settings.sky_span = int(run->parsed.sky_span);
  settings.sky_max_span = int(run->parsed.sky_max_span);
  if (kiosk) {
    std::vector<std::string> brush_errors;
    bool brush_ok = loadBrushConfig(configFile("brush.toml"), &run->brush, &brush_errors);
    if (const std::string local = configOverrideFile("brush.toml"); !local.empty())
      brush_ok = loadBrushConfig(local, &run->brush, &brush_errors) && brush_ok;
    if (!brush_ok && kiosk_problem.empty() && !brush_errors.empty())
      kiosk_problem = brush_errors.front();
  } else {
    run->brush = loadDefaultBrushConfig();
  }
  settings.auto_end_still_ms = run->brush.stroke.auto_end_still_ms;
  settings.auto_end_light_ms = run->brush.stroke.auto_end_light_ms;
  return -1;
}

// The painter's session (resumed from --resume, else new; the kiosk makes one per visitor), its
// sync sender and starting point (--open): -1 when they hold, else the exit status.
int startPaintSession(Args& args, PaintRun* run) {
  std::string error;
  const bool kiosk = run->parsed.kiosk;
  const std::string& resume_path = run->parsed.resume_path;
  if (kiosk && args.has("open")) return fail("--open is not a kiosk option", 2);
  if (kiosk && !resume_path.empty()) return fail("--resume is not a kiosk option", 2);
  if (kiosk && args.has("sync-udp"))
    return fail(
        "--sync-udp is not a kiosk option: visitors' sessions are not synchronised with a "
        "study's recorder (use `cloudbrush paint --sync-udp` or `cloudbrush study`), and the "
        "kiosk's unit allows no IP sockets",
        2);
  if (run->pen && !kiosk) {  // the kiosk makes a session per visitor (kiosk_screen.h)
    if (!resume_path.empty()) {
      ResumedSession resumed;
      if (!resumeOrStartSession(resume_path, run->settings, run->brush, run->mapping, &run->journal,
                                &resumed, &error))
        return fail("--resume: " + error, 2);
      reportResumed(resume_path, resumed);
      run->session = std::move(resumed.session);
      run->resuming = resumed.resumed;
      run->resumed_after_ns = resumed.last_sample_ns;
      if (run->resuming)
        run->parsed.loop_options.orbit_degrees_per_second = 0.0f;  // the view stays as it was
    } else {
      run->session = std::make_unique<PaintSession>(run->settings, run->brush, run->mapping);
    }
  }
  if (args.has("sync-udp")) {
    if (!run->sync_sender.open(args.get("sync-udp", ""), &error))
      return fail("--sync-udp: " + error, 2);
    if (run->session) run->session->setSyncSender(&run->sync_sender);
  }
  if (run->session && !run->resuming) {
    // The render settings in force, journalled with the brush and mapping.
    run->session->setRenderSettings(formatRenderConfig(run->render_config), 0);
    run->session->setStartingLight(run->light);
    run->session->setStartingStyle(renderStyleName(run->render_config.options.style));
    if (args.has("open")) {
      // Start from a saved cloud (a task's starting point, an artist's earlier work).
      const std::string path = args.get("open", "");
      try {
        if (!run->session->replaceVolume(loadVolume(path), 0, path, &error)) return fail(error, 2);
      } catch (const std::exception& e) {
        return fail(std::string("--open: ") + e.what(), 2);
      }
    }
  }
  return -1;
}

// Where the run writes (the kiosk: all under the data dir, checked), and with --resume and
// --backend replay, the recorded pen carrying on after the last sample the session holds.
void prepareRecording(const Args& args, PaintRun* run) {
  const bool kiosk = run->parsed.kiosk;
  // Kiosk: everything it writes goes under the data dir (the state dir is not even created).
  run->data_dir = args.has("data-dir") ? args.get("data-dir", "") : stateDir();
  // The journal starts when a pen first connects (a kiosk without a tablet records nothing).
  if (kiosk && run->parsed.kiosk_problem.empty()) {
    std::string dir_error;
    if (!checkDataDir(run->data_dir, &dir_error)) run->parsed.kiosk_problem = dir_error;
  }
  run->session_dir = args.get("session-dir", (kiosk ? run->data_dir : stateDir()) + "/sessions");
  run->record = !args.has("no-record");
  if (run->resuming && run->parsed.backend == "replay" && run->resumed_after_ns >= 0) {
    // The recorded pen carries on after the last sample the resumed session holds.
    JournalReadResult input = readJournal(args.get("journal", ""));
    std::vector<JournalRecord> rest;
    for (JournalRecord& r : input.records)
      if (r.type != JournalRecordType::kPenSample || r.t_ns > run->resumed_after_ns)
        rest.push_back(std::move(r));
    run->pen = std::make_unique<ReplayPenSource>(std::move(rest), ReplayOptions{});
  }
}

// The kiosk's service: READY after the first frame, watchdog pings from the loop itself (a hung
// loop stops them and systemd restarts the service), health.json for remote checks.
void startKioskService(PaintRun& run, const MonotonicClock& clock,
                       std::optional<KioskService>* service,
                       std::unique_ptr<KioskScreen>* kiosk_screen) {
  PaintLoopOptions& loop_options = run.parsed.loop_options;
  std::string watchdog_error;
  const std::optional<WatchdogTimeout> watchdog = watchdogTimeoutFromEnvironment(&watchdog_error);
  if (!watchdog_error.empty())
    std::fprintf(stderr, "cloudbrush kiosk: %s\n", watchdog_error.c_str());
  service->emplace(SdNotifier::fromEnvironment(), watchdog, clock, run.data_dir, run.pen.get(),
                   [](const std::string& problem) {
                     std::fprintf(stderr, "cloudbrush kiosk: %s\n", problem.c_str());
                   });
  loop_options.each_iteration = [service, kiosk_screen](bool presented) {
    if (*kiosk_screen) (*service)->setCounts((*kiosk_screen)->counts());
    (*service)->onIteration(presented);
  };
  loop_options.orbit_degrees_per_second = 0.0f;  // the attract loop orbits; visitors paint
  loop_options.clock = &clock;
  loop_options.before_start_again = [kiosk_screen]() {
    if (*kiosk_screen) (*kiosk_screen)->keepFinishedCloud("start again");
  };
}

// What the kiosk screen is made with: the painter's configs, texts, attract journal, and the
// service's hooks. A failure to load the texts becomes the kiosk's problem.
KioskSetup makeKioskSetup(PaintRun& run, KioskService* service) {
  const KioskConfig& kiosk_config = run.parsed.kiosk_config;
  KioskSetup setup;
  std::string error;
  setup.config = kiosk_config;
  if (!loadKioskAssets(kiosk_config, &setup, &error) && run.parsed.kiosk_problem.empty())
    run.parsed.kiosk_problem = error;
  setup.data_dir = run.data_dir;
  setup.config_dir = defaultConfigDir();
  setup.visitor_settings = run.settings;
  setup.brush = run.brush;
  setup.mapping = run.mapping;
  setup.light = run.light;
  setup.style = renderStyleName(run.render_config.options.style);
  setup.render = run.render_config.options;
  setup.render_settings = formatRenderConfig(run.render_config);
  setup.moving_scale = run.parsed.loop_options.moving_scale;
  setup.record_journals = run.record;
  setup.on_status = [service](const std::string& status) { service->onStatus(status); };
  setup.on_input = [service]() { service->onInput(); };
  setup.on_problem = [service](const std::string& problem) { service->onProblem(problem); };
  setup.on_storage = [service](const std::string& problem) { service->onStorage(problem); };
  return setup;
}

// On a display: the paint loop (the kiosk's screen and service around it) until Esc, a signal,
// --frames or --seconds; the exit status.
int runPainter(PaintRun& run, const Args& args, const Volume& volume, VolumeRenderer& renderer) {
  std::string error;
  Display& display = *run.display;
  PaintLoopOptions& loop_options = run.parsed.loop_options;
  const bool kiosk = run.parsed.kiosk;
  std::string& kiosk_problem = run.parsed.kiosk_problem;
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  if (kiosk)
    std::fprintf(stderr,
                 "cloudbrush: kiosk: visitor mode (quit keys and operator commands are ignored; "
                 "stop the service to end); the sky clears after %.0f s without input\n",
                 run.parsed.kiosk_config.idle_seconds);
  else
    std::fprintf(stderr,
                 "cloudbrush: H shows the keys; Esc or q quits (asks with unsaved work), 1-5 "
                 "modes, M menu, B brush, N mapping, Ctrl+Z/Y undo/redo%s\n",
                 run.pen ? "; bring the pen near the tablet to paint" : "");
  loop_options.config_dir = defaultConfigDir();
  loop_options.state_dir = kiosk ? run.data_dir : stateDir();
  // --place FILE: a picture (PNG) or model (OBJ, PLY, glTF) made into a cloud from the starting
  // view as the session begins, journalled like any edit.
  const std::string place = args.get("place", "");
  loop_options.on_first_connection = [&run, &place]() {
    // The kiosk journals each visitor itself.
    if (run.record && run.session && !run.resuming)
      startSessionJournal(run.session.get(), &run.journal, run.parsed.resume_path, run.session_dir);
    if (place.empty() || !run.session) return;
    const std::string ext = std::filesystem::path(place).extension().string();
    const bool model = ext != ".png" && ext != ".PNG";
    std::string place_error;
    if (!run.session->apply(ui::PlaceShape{model, place}, 0, &place_error))
      std::fprintf(stderr, "cloudbrush: --place: %s\n", place_error.c_str());
  };
  const MonotonicClock clock;
  std::optional<KioskService> service;
  std::unique_ptr<KioskScreen> kiosk_screen;
  if (kiosk) startKioskService(run, clock, &service, &kiosk_screen);
  // Durability: the journal syncs at every stroke end (PaintSession) and, from the
  // frame loop, whenever records older than a second are not yet on the disk.
  {
    const std::function<void(bool)> kiosk_iteration = loop_options.each_iteration;
    JournalWriter& journal = run.journal;
    loop_options.each_iteration = [&journal, &clock, kiosk_iteration](bool presented) {
      if (journal.isOpen() && !journal.syncIfDue(clock.nowNs()))
        std::fprintf(stderr, "cloudbrush: journal: %s\n", journal.error().c_str());
      if (kiosk_iteration) kiosk_iteration(presented);
    };
  }
  PaintLoop loop(display, renderer, volume, run.light, loop_options);
  if (run.pen) loop.attachPen(run.pen.get(), run.session.get());
  if (kiosk) {
    KioskSetup setup = makeKioskSetup(run, &*service);
    service->setMetricsDir(run.parsed.kiosk_config.metrics_dir);
    try {
      if (kiosk_problem.empty())
        kiosk_screen = std::make_unique<KioskScreen>(display, renderer, loop.screen(),
                                                     run.pen.get(), clock, std::move(setup));
    } catch (const std::exception& e) {
      kiosk_problem = e.what();
    }
    if (!kiosk_problem.empty())
      return runKioskErrorScreen(display, *service, kiosk_problem, loop_options, &g_stop);
  }
  PaintLoopSummary summary;
  const bool ran = loop.run(&g_stop, &summary, &error, kiosk_screen.get());
  if (kiosk) {
    // Stopped by SIGTERM (systemctl stop, shutdown) mid-visit: the visitor's cloud is kept.
    if (summary.quit_reason == "signal") kiosk_screen->stopping();
    service->stopping();
    std::printf("cloudbrush kiosk: %ld visits, %ld idle resets, %zu clouds kept in the gallery\n",
                kiosk_screen->visits(), kiosk_screen->idleResets(),
                kiosk_screen->gallerySaved().size());
  }
  if (!ran) return fail(error);
  printPaintSummary(summary, display, run.pen.get(), run.session.get(), run.parsed.grid,
                    run.resuming);
  if (summary.quit_reason == "operator shutdown") return kOperatorShutdownExitStatus;
  return 0;
}

}  // namespace

int commandPaint(int argc, char** argv) {
  std::string error;
  Args args(argc, argv, {"help", "stats", "no-record", "kiosk"});
  if (args.has("help")) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  const auto unknown = args.unknown(
      {"help",       "stats",        "display",      "drm-device",      "size",     "out-dir",
       "grid",       "seed",         "orbit",        "moving-scale",    "frames",   "backend",
       "pen-device", "journal",      "session-dir",  "no-record",       "keys",     "open",
       "place",      "kiosk",        "idle-seconds", "warning-seconds", "data-dir", "seconds",
       "language",   "gallery",      "resume",       "sync-udp",        "morph-to", "morph-seconds",
       "sky-span",   "sky-max-span", "metrics-dir"});
  if (!unknown.empty()) return fail("unknown option " + unknown.front() + " (see --help)", 2);
  if (args.positional().size() > 1)
    return fail("unexpected argument '" + args.positional()[1] + "' (see --help)", 2);
  // Before any thread starts (app/kiosk/kiosk_heap.h).
  if (args.has("kiosk") && !setKioskHeapPolicy())
    std::fprintf(stderr, "cloudbrush: kiosk: glibc refused the heap settings (kiosk_heap.h)\n");

  PaintRun run;
  if (const int status = parsePaintArgs(args, &run.parsed); status >= 0) return status;
  run.display = openPaintDisplay(args, run.parsed, &error);
  if (!run.display) return fail(error);
  run.headless = std::string(run.display->platformName()) == "surfaceless" &&
                 !args.has("backend") && !run.parsed.kiosk;
  if (const int status = openConfigsAndPen(args, &run); status >= 0) return status;
  if (const int status = startPaintSession(args, &run); status >= 0) return status;
  prepareRecording(args, &run);

  const long grid = run.parsed.grid, seed = run.parsed.seed;
  const auto generate_start = std::chrono::steady_clock::now();
  // Shown until a pen connects; then the session's volume (empty at first) is painted into.
  const Volume demo_volume =
      placeInSky(makeBundledCumulus(glm::ivec3(int(grid)), uint32_t(seed)), run.parsed.sky);
  std::fprintf(
      stderr, "cloudbrush: bundled cloud %ld³ (seed %ld) in %.0f ms\n", grid, seed,
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - generate_start)
          .count());
  VolumeRenderer renderer;
  if (!renderer.init(&error)) return fail(error);

  if (run.headless) {
    const PaintLoopOptions& loop_options = run.parsed.loop_options;
    HeadlessRenderResult result;
    if (!renderHeadless(*run.display, renderer, demo_volume, run.light, loop_options.render,
                        args.get("out-dir", "out"), "cloudbrush-cumulus", loop_options.print_stats,
                        &result, &error))
      return fail(error);
    if (loop_options.print_stats) std::fprintf(stderr, "%s\n", result.stats.summary().c_str());
    for (const std::string& path : result.written) std::printf("%s\n", path.c_str());
    return 0;
  }
  return runPainter(run, args, demo_volume, renderer);
}

}  // namespace cb
