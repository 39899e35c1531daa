// The kiosk soak: hours of kiosk time compressed by driving the kiosk headless from
// the injectable clock. The real parts as `cloudbrush kiosk` wires them — EGL surfaceless on
// llvmpipe, the bundled config (kiosk.toml, brush, mapping, render) and attract journal, the
// shell's frame loop running KioskScreen over the painter, KioskService (sd_notify, watchdog
// pings, health.json) — on a ManualClock that the director below moves on after every loop
// iteration. Visitors are replayed sessions: strokes recorded in the bundled attract journal,
// drawn at their recorded pace, shifted across the tablet and re-timed per visitor (seeded), with
// undo, "start again" and a view change among them. Each cycle is attract → visitor → idle
// countdown → reset → attract.
//
// Checked (exit status 1 and a FAILED line when not):
//   - the final VmRSS (after the last reset) is within 2% (--rss-band-percent; the CI run asks for
//     5%, see SoakOptions) of the median over the reference window
//     (the first simulated hour after the warm-up), either way, sampled after every reset once
//     the next visitor's fresh session is made;
//   - the open file descriptors after every reset past the warm-up are all the same;
//   - no frame-loop stall on the real monotonic clock (time between two loop iterations, from
//     the first frame) reaches the watchdog's ping interval (half the unit's WatchdogSec=), so
//     the pings could never have stopped;
//   - every visit ended in an idle reset and every stroke was mapped;
//   - systemd's side (a datagram socket this process binds and hands to the kiosk process as
//     NOTIFY_SOCKET, with the unit's WATCHDOG_USEC) received READY once, STATUS at every screen
//     change, WATCHDOG every ping interval of simulated time and STOPPING;
//   - with --strace the kiosk process runs under `strace -f -e trace=%file`: every file it wrote,
//     created, renamed or removed is inside its data directory.
//
// The kiosk runs in a child process (this program with --child): the parent plays systemd and
// reads the strace log, so nothing it does shows in the trace.
//
//   build/tests/unit/kiosk/kiosk_soak --hours 8 --strace      # the long soak (README)
//   ... --memory-detail    # after every reset, where VmRSS is (tests/support/process_memory.h)
//                          # and what the renderer holds (pool, frame targets, light volume)
#include <signal.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "app/brush/brush_config.h"
#include "app/core/config_paths.h"
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
#include "app/shell/kiosk/kiosk_screen.h"
#include "app/shell/painter/paint_loop.h"
#include "app/shell/painter/paint_screen.h"
#include "app/volume/scene_generators.h"
#include "drivers/core/clock.h"
#include "drivers/core/journal.h"
#include "drivers/core/pen_source.h"
#include "tests/support/command_line.h"
#include "tests/support/process_memory.h"
#include "tests/support/strace_file_writes.h"
#include "tests/unit/kiosk/notify_socket_listener.h"

namespace cb {
namespace {

namespace fs = std::filesystem;
constexpr int64_t kSecond = 1'000'000'000;

struct SoakOptions {
  double hours = 0.25;              // simulated kiosk time
  double warmup_minutes = 10.0;     // not judged: shader cache, first allocations
  double reference_minutes = 60.0;  // the window whose median VmRSS the final one is held to
  // The band the final VmRSS must stay in around the reference median, either way: the issue's
  // 2 %, held by the long soak. The CI run (0.2 h) has 3 resets to a reference window, and RSS
  // moves about ±3 % from one visit to the next (234.7–241.9 MB measured), so it asks for 5 %.
  double rss_band_percent = 2.0;
  int width = 1280, height = 720;  // the product's default display size
  int grid = 256;                  // and volume
  int strokes_per_visit = 24;
  double attract_min_s = 60.0, attract_max_s = 300.0;  // nobody at the kiosk
  double stroke_step_s = 0.1;  // clock step per iteration while a visitor's pen is down or near
  double idle_step_s = 2.0;    // otherwise (attract loop, idle countdown)
  uint32_t seed = 1;
  std::string data_dir;  // default: a fresh temporary directory
  bool strace = false;
  bool memory_detail = false;  // a breakdown of resident memory after every reset
  bool child = false;
};

// The options, or false after saying what is wrong on stderr.
bool parseArgs(int argc, char** argv, SoakOptions* o) {
  const auto real = [](double* field) {
    return [field](const std::string& v) { *field = std::stod(v); };
  };
  const auto integer = [](int* field) {
    return [field](const std::string& v) { *field = std::stoi(v); };
  };
  const auto setTrue = [](bool* field) { return [field](const std::string&) { *field = true; }; };
  const std::vector<test::CommandOption> options = {
      {"--hours", real(&o->hours)},
      {"--warmup-minutes", real(&o->warmup_minutes)},
      {"--reference-minutes", real(&o->reference_minutes)},
      {"--rss-band-percent", real(&o->rss_band_percent)},
      {"--size",
       [o](const std::string& v) { test::parseSizeOption("--size", v, &o->width, &o->height); }},
      {"--grid", integer(&o->grid)},
      {"--strokes-per-visit", integer(&o->strokes_per_visit)},
      {"--attract-seconds",
       [o](const std::string& v) {
         if (std::sscanf(v.c_str(), "%lf-%lf", &o->attract_min_s, &o->attract_max_s) != 2)
           throw std::runtime_error("--attract-seconds: expected MIN-MAX, got '" + v + "'");
       }},
      {"--idle-step", real(&o->idle_step_s)},
      {"--stroke-step", real(&o->stroke_step_s)},
      {"--seed", [o](const std::string& v) { o->seed = uint32_t(std::stoul(v)); }},
      {"--data-dir", [o](const std::string& v) { o->data_dir = v; }},
      {"--strace", setTrue(&o->strace), true},
      {"--memory-detail", setTrue(&o->memory_detail), true},
      {"--child", setTrue(&o->child), true},
  };
  if (!test::parseCommandLine("kiosk_soak", argc, argv, options)) return false;
  if (!(o->hours > 0.0) || o->grid < 8 || o->strokes_per_visit < 1 || o->width < 64 ||
      o->height < 64 || o->attract_max_s < o->attract_min_s || o->attract_min_s < 0.0 ||
      !(o->idle_step_s > 0.0) || !(o->stroke_step_s > 0.0)) {
    std::fprintf(stderr,
                 "kiosk_soak: bad values (hours > 0, grid >= 8, strokes per visit >= 1, size >= "
                 "64x64)\n");
    return false;
  }
  return true;
}

// ---- the replayed visitors -------------------------------------------------------------------

using Stroke = std::vector<PenSample>;  // proximity in ... proximity out, t_ns from 0

// The strokes of a recorded journal: each from its first sample in proximity to the first out
// of proximity after it, timed from its first sample.
std::vector<Stroke> strokesOf(const std::vector<JournalRecord>& records, PenDeviceInfo* info) {
  std::vector<Stroke> strokes;
  Stroke current;
  bool have_info = false;
  for (const JournalRecord& r : records) {
    if (r.type == JournalRecordType::kDevice && !have_info) {
      if (auto d = decodeDeviceInfo(r.payload)) *info = *d, have_info = true;
      continue;
    }
    if (r.type != JournalRecordType::kPenSample) continue;
    const std::optional<PenSample> s = decodePenSample(r.payload);
    if (!s || (current.empty() && !s->in_proximity)) continue;
    current.push_back(*s);
    if (!s->in_proximity) {
      bool touched = false;
      for (const PenSample& p : current) touched = touched || (p.buttons & kPenTip);
      const int64_t t0 = current.front().t_ns;
      for (PenSample& p : current) p.t_ns -= t0;
      if (touched) strokes.push_back(std::move(current));
      current.clear();
    }
  }
  return strokes;
}

struct TimedCommand {
  int64_t t_ns;
  Command command;
};

struct Visit {
  std::vector<PenSample> samples;  // t_ns from the visit's start
  std::vector<TimedCommand> commands;
  int strokes = 0;
};

// Visitor `index`: strokes drawn from `pool` (seeded), each moved by an offset that keeps it on
// the tablet, 0.5–2.5 s apart; an undo after every seventh stroke, a view change in some visits,
// "start again" (Delete) half-way through every fourth.
Visit makeVisit(const std::vector<Stroke>& pool, const PenDeviceInfo& info, long index, int strokes,
                uint32_t seed) {
  std::mt19937 rng(seed * 7919u + uint32_t(index));
  std::uniform_int_distribution<size_t> pick(0, pool.size() - 1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Visit visit;
  int64_t t = 0;
  for (int k = 0; k < strokes; ++k) {
    const Stroke& stroke = pool[pick(rng)];
    int32_t x0 = info.x_max, x1 = 0, y0 = info.y_max, y1 = 0;
    for (const PenSample& s : stroke) {
      x0 = std::min(x0, s.x_raw), x1 = std::max(x1, s.x_raw);
      y0 = std::min(y0, s.y_raw), y1 = std::max(y1, s.y_raw);
    }
    // An offset within what keeps the stroke on the tablet.
    const int32_t dx = int32_t(std::lround((unit(rng) - 0.5) * 0.3 * info.x_max));
    const int32_t dy = int32_t(std::lround((unit(rng) - 0.5) * 0.3 * info.y_max));
    const int32_t sx = std::clamp(dx, -x0, info.x_max - x1);
    const int32_t sy = std::clamp(dy, -y0, info.y_max - y1);
    for (PenSample s : stroke) {
      s.t_ns += t;
      s.x_raw += sx, s.y_raw += sy;
      if (info.x_res > 0.0) s.x_mm = s.x_raw / info.x_res;
      if (info.y_res > 0.0) s.y_mm = s.y_raw / info.y_res;
      visit.samples.push_back(s);
    }
    t = visit.samples.back().t_ns + int64_t((0.5 + 2.0 * unit(rng)) * 1e9);
    ++visit.strokes;
    if (k % 7 == 6) visit.commands.push_back({t - kSecond / 4, Command::kUndo});
    if (k == strokes / 3 && index % 3 == 1)
      visit.commands.push_back({t - kSecond / 4, Command::kViewLeft});
    if (k == strokes / 2 && index % 4 == 3)
      visit.commands.push_back({t - kSecond / 4, Command::kDeleteAll});
  }
  return visit;
}

// A tablet whose pen plays one visit at a time at its recorded pace on the clock; connected and
// silent in between.
class VisitorPen final : public PenSource {
 public:
  VisitorPen(const Clock& clock, PenDeviceInfo info) : clock_(clock), info_(std::move(info)) {}
  const char* backendName() const override { return "replayed visitors"; }
  void poll(int, std::vector<PenSample>& out) override {
    const int64_t now = clock_.nowNs();
    for (; next_ < samples_.size() && start_ns_ + samples_[next_].t_ns <= now; ++next_) {
      PenSample s = samples_[next_];
      s.t_ns += start_ns_;
      out.push_back(s);
    }
  }
  PenConnection connection() const override { return PenConnection::kConnected; }
  const PenDeviceInfo& deviceInfo() const override { return info_; }
  std::string statusMessage() const override { return "replayed visitors"; }

  void play(std::vector<PenSample> samples, int64_t start_ns) {
    samples_ = std::move(samples);
    next_ = 0;
    start_ns_ = start_ns;
  }
  bool done() const { return next_ >= samples_.size(); }

 private:
  const Clock& clock_;
  PenDeviceInfo info_;
  std::vector<PenSample> samples_;
  size_t next_ = 0;
  int64_t start_ns_ = 0;
};

// ---- process figures -------------------------------------------------------------------------

long vmRssKb() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

int openFdsNow() {
  int n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator("/proc/self/fd")) ++n;
  return n - 1;  // the directory iterator's own
}

// The kiosk's threads (pen reader, attract replay, health file) open and close files of their own
// at any moment, so one reading can hold a file that is about to close (seen once in six CI runs:
// 6 fds at one reset, 5 at all others). A leaked descriptor stays open: the fewest of three
// readings 20 ms apart still counts it.
int openFds() {
  int fewest = openFdsNow();
  for (int i = 0; i < 2; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    fewest = std::min(fewest, openFdsNow());
  }
  return fewest;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// WatchdogSec= of the bundled unit, in seconds.
double unitWatchdogSeconds() {
  std::ifstream in(std::string(CB_SOURCE_DIR) + "/config/systemd/cloudbrush-kiosk.service");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("WatchdogSec=", 0) == 0) return std::stod(line.substr(12));
  throw std::runtime_error("no WatchdogSec= in config/systemd/cloudbrush-kiosk.service");
}

// ---- the kiosk (child process) ---------------------------------------------------------------

std::atomic<bool> g_stop{false};

struct ResetSample {
  double sim_s;
  long rss_kb;
  int fds;
};

// What `cloudbrush kiosk` loads before its loop (app/cli/command_paint.cpp), and the strokes of
// the attract journal the visitors replay.
struct KioskParts {
  std::string config_dir;
  KioskSetup setup;
  RenderConfig render_config;
  BrushConfig brush;
  PenDeviceInfo tablet{};
  std::vector<Stroke> pool;
};

KioskParts loadKioskParts() {
  KioskParts parts;
  parts.config_dir = defaultConfigDir();
  const auto configPath = [&](const std::string& name) { return parts.config_dir + "/" + name; };
  KioskSetup& setup = parts.setup;
  setup.config = loadKioskConfig(configPath("kiosk.toml"));
  setup.texts = KioskTexts::load(
      configPath("kiosk/texts.toml"), setup.config.language,
      [](const std::string& line) { std::fprintf(stderr, "kiosk_soak: %s\n", line.c_str()); });
  parts.render_config = loadRenderConfig(configPath("render.toml"));
  parts.brush = loadDefaultBrushConfig();
  JournalReadResult attract = readJournal(configPath(setup.config.attract_journal));
  if (!attract.error.empty()) throw std::runtime_error("attract journal: " + attract.error);
  parts.pool = strokesOf(attract.records, &parts.tablet);
  if (parts.pool.empty() || parts.tablet.x_max <= 0)
    throw std::runtime_error("no strokes to replay");
  setup.config_dir = parts.config_dir;
  setup.attract_journal = std::move(attract.records);
  setup.brush = parts.brush;
  setup.mapping = loadMappingConfig(configPath("mapping.toml"));
  setup.light = parts.render_config.light;
  setup.style = renderStyleName(parts.render_config.options.style);
  setup.render = parts.render_config.options;
  setup.render_settings = formatRenderConfig(parts.render_config);
  setup.moving_scale = parts.render_config.moving_scale;
  return parts;
}

// The director: after every frame-loop iteration, what happens next at the kiosk (a visitor
// arrives, plays their strokes and commands, leaves; the idle reset), the clock's step, and the
// figures the soak is judged on (VmRSS and fds after each reset, the real-clock stalls).
class SoakDirector {
 public:
  SoakDirector(const SoakOptions& o, const KioskParts& parts, ManualClock& clock, VisitorPen& pen,
               KioskService& service, VolumeRenderer& renderer)
      : o_(o),
        parts_(parts),
        clock_(clock),
        pen_(pen),
        service_(service),
        renderer_(renderer),
        rng_(o.seed),
        attract_s_(o.attract_min_s, o.attract_max_s),
        end_ns_(clock.nowNs() + int64_t(o.hours * 3600.0 * 1e9)),
        next_visit_ns_(clock.nowNs() + int64_t(attract_s_(rng_) * 1e9)),
        steady_start_(std::chrono::steady_clock::now()) {}

  void watch(KioskScreen* kiosk) { kiosk_ = kiosk; }

  void onIteration(bool presented) {
    service_.onIteration(presented);
    ++iterations_;
    frames_ += presented;
    timeIteration();
    const int64_t now = clock_.nowNs();
    switch (phase_) {
      case Phase::kAttract:
        onAttract(now);
        break;
      case Phase::kVisiting:
        onVisiting(now);
        break;
      case Phase::kLeft:
        onLeft(now);
        break;
    }
    if (long(simS() / 3600.0) > hour_reported_) reportHour(++hour_reported_);
    clock_.advance(int64_t((phase_ == Phase::kVisiting ? o_.stroke_step_s : o_.idle_step_s) * 1e9));
  }

  // After the loop: a reset whose figures were still to be read is read now.
  void finish() {
    if (!sample_pending_) return;
    resets_.back().rss_kb = vmRssKb();
    resets_.back().fds = openFds();
  }

  int judge(const Display& display, double ping_interval_s) const;

 private:
  enum class Phase { kAttract, kVisiting, kLeft };

  double simS() const { return double(clock_.nowNs() - kSecond) / 1e9; }
  double realS() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - steady_start_).count();
  }

  // Real time between iterations, from the first frame on (READY: systemd's watchdog runs), and
  // the process's CPU time over the same iteration (all threads: llvmpipe's too), which says what
  // the iteration costs when the machine is not shared.
  void timeIteration() {
    const int64_t real_now = std::chrono::duration_cast<std::chrono::nanoseconds>(
                                 std::chrono::steady_clock::now().time_since_epoch())
                                 .count();
    timespec cpu_ts{};
    ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &cpu_ts);
    const int64_t cpu_now = int64_t(cpu_ts.tv_sec) * kSecond + cpu_ts.tv_nsec;
    if (service_.readySent() && last_real_ > 0) {
      const double gap = double(real_now - last_real_) / 1e9;
      const double cpu = double(cpu_now - last_cpu_) / 1e9;
      max_cpu_s_ = std::max(max_cpu_s_, cpu);
      if (gap > 2.0 && ++stalls_over_2s_ <= 10)
        std::printf("kiosk_soak: iteration of %.2f s (%.2f s of CPU) at simulated %.0f s (%s)\n",
                    gap, cpu, simS(), KioskScreen::stateName(kiosk_->state()));
      if (gap > max_stall_s_) {
        max_stall_s_ = gap;
        max_stall_cpu_s_ = cpu;
        max_stall_at_s_ = simS();
        max_stall_state_ = KioskScreen::stateName(kiosk_->state());
      }
    }
    last_real_ = service_.readySent() ? real_now : 0;
    last_cpu_ = cpu_now;
  }

  void onAttract(int64_t now) {
    if (sample_pending_ && kiosk_->nextVisitorReady()) {
      // Sampled once the reset is complete: the cleared sky on the attract loop, the finished
      // visitor's session given back and the next visitor's fresh one made.
      resets_.back().rss_kb = vmRssKb();
      resets_.back().fds = openFds();
      std::printf("kiosk_soak: reset %zu at simulated %.0f s: VmRSS %.1f MB, %d fds\n",
                  resets_.size(), resets_.back().sim_s, double(resets_.back().rss_kb) / 1024.0,
                  resets_.back().fds);
      if (o_.memory_detail) printMemoryDetail();
      sample_pending_ = false;
      if (now >= end_ns_) g_stop.store(true);
    }
    if (!sample_pending_ && now >= next_visit_ns_) {
      visit_ = makeVisit(parts_.pool, parts_.tablet, visits_, o_.strokes_per_visit, o_.seed);
      pen_.play(visit_.samples, now);
      visit_start_ns_ = now;
      next_command_ = 0;
      strokes_fed_ += visit_.strokes;
      ++visits_;
      phase_ = Phase::kVisiting;
    }
  }

  void noteStrokesMapped() {
    if (kiosk_->state() == KioskScreen::State::kVisitor && kiosk_->visitorSession())
      visit_strokes_mapped_ = kiosk_->visitorSession()->strokesMapped();
  }

  void onVisiting(int64_t now) {
    noteStrokesMapped();
    for (; next_command_ < visit_.commands.size() &&
           now - visit_start_ns_ >= visit_.commands[next_command_].t_ns;
         ++next_command_)
      kiosk_->onCommand(visit_.commands[next_command_].command, now);
    if (pen_.done() && next_command_ == visit_.commands.size()) phase_ = Phase::kLeft;
  }

  void onLeft(int64_t now) {
    noteStrokesMapped();
    if (kiosk_->state() != KioskScreen::State::kAttract) return;
    // The idle reset.
    strokes_mapped_ += visit_strokes_mapped_;
    visit_strokes_mapped_ = 0;
    resets_.push_back({simS(), 0, 0});
    sample_pending_ = true;
    next_visit_ns_ = now + int64_t(attract_s_(rng_) * 1e9);
    phase_ = Phase::kAttract;
  }

  void printMemoryDetail() const {
    const RendererGpuMemory gpu = renderer_.gpuMemory();
    const PaintSession* v = kiosk_->visitorSession();
    std::printf(
        "kiosk_soak:   %s | renderer pool %.1f occupancy %.1f targets %.1f "
        "styles %.1f MB; light %.1f tables %.1f attract vol %.1f visitor vol %.1f "
        "hist %.1f MB; attract scale %.2f\n",
        test::describe(test::readProcessMemory()).c_str(), gpu.pool / 1048576.0,
        gpu.occupancy / 1048576.0, gpu.frame_targets / 1048576.0, gpu.styles / 1048576.0,
        renderer_.lightVolume().memoryBytes() / 1048576.0,
        renderer_.brickPool().tableBytes() / 1048576.0,
        kiosk_->attract().volume().memoryBytes() / 1048576.0,
        v ? v->volume().memoryBytes() / 1048576.0 : 0.0,
        v ? v->history().copyBytes() / 1048576.0 : 0.0, double(kiosk_->attract().scale()));
  }

  void reportHour(long hour) const {
    std::vector<double> rss;
    int fd_min = 1 << 30, fd_max = 0;
    for (const ResetSample& r : resets_)
      if (r.rss_kb > 0 && r.sim_s > double(hour - 1) * 3600.0 && r.sim_s <= double(hour) * 3600.0) {
        rss.push_back(double(r.rss_kb));
        fd_min = std::min(fd_min, r.fds), fd_max = std::max(fd_max, r.fds);
      }
    std::printf(
        "kiosk_soak: simulated %.2f h (real %.0f s): %ld visits, %ld strokes mapped; after the "
        "resets of this hour VmRSS median %.1f MB, fds %d..%d; longest loop stall so far %.2f s\n",
        simS() / 3600.0, realS(), visits_, strokes_mapped_, median(rss) / 1024.0,
        rss.empty() ? 0 : fd_min, rss.empty() ? 0 : fd_max, max_stall_s_);
    std::fflush(stdout);
  }

  const SoakOptions& o_;
  const KioskParts& parts_;
  ManualClock& clock_;
  VisitorPen& pen_;
  KioskService& service_;
  VolumeRenderer& renderer_;
  KioskScreen* kiosk_ = nullptr;
  Phase phase_ = Phase::kAttract;
  std::mt19937 rng_;
  std::uniform_real_distribution<double> attract_s_;
  int64_t end_ns_, next_visit_ns_, visit_start_ns_ = 0;
  Visit visit_;
  size_t next_command_ = 0;
  long visits_ = 0, strokes_fed_ = 0, strokes_mapped_ = 0, iterations_ = 0, frames_ = 0;
  uint32_t visit_strokes_mapped_ = 0;
  std::vector<ResetSample> resets_;
  double max_stall_s_ = 0.0, max_stall_at_s_ = 0.0, max_stall_cpu_s_ = 0.0, max_cpu_s_ = 0.0;
  std::string max_stall_state_;
  int64_t last_real_ = 0, last_cpu_ = 0;
  long stalls_over_2s_ = 0, hour_reported_ = 0;
  bool sample_pending_ = false;  // a reset whose VmRSS and fds are still to be read
  std::chrono::steady_clock::time_point steady_start_;
};

// The soak's verdict: prints the figures and a FAILED line per check missed; 0 when none.
int SoakDirector::judge(const Display& display, double ping_interval_s) const {
  const int64_t warmup_end_ns = kSecond + int64_t(o_.warmup_minutes * 60e9);
  const int64_t reference_end_ns = warmup_end_ns + int64_t(o_.reference_minutes * 60e9);
  std::vector<std::string> failures;
  std::vector<double> reference;
  for (const ResetSample& r : resets_)
    if (r.sim_s * 1e9 > double(warmup_end_ns - kSecond) &&
        r.sim_s * 1e9 <= double(reference_end_ns - kSecond))
      reference.push_back(double(r.rss_kb));
  const double reference_kb = median(reference);
  const double final_kb = resets_.empty() ? 0.0 : double(resets_.back().rss_kb);
  const double drift = reference_kb > 0.0 ? (final_kb - reference_kb) / reference_kb : 1.0;
  int fd_min = 1 << 30, fd_max = 0;
  size_t judged = 0;
  for (const ResetSample& r : resets_)
    if (r.sim_s * 1e9 > double(warmup_end_ns - kSecond)) {
      fd_min = std::min(fd_min, r.fds), fd_max = std::max(fd_max, r.fds);
      ++judged;
    }
  if (reference.size() < 3)
    failures.push_back("only " + std::to_string(reference.size()) +
                       " resets in the reference window (run longer)");
  // The check, both ways: the final VmRSS within the band (2 %) of the reference median.
  const double band = o_.rss_band_percent / 100.0;
  if (std::abs(drift) > band)
    failures.push_back("final VmRSS " + std::to_string(long(final_kb)) + " kB is " +
                       std::to_string(drift * 100.0) + "% off the reference median " +
                       std::to_string(long(reference_kb)) + " kB (within " +
                       std::to_string(o_.rss_band_percent) + "% wanted)");
  if (judged == 0 || fd_max != fd_min)
    failures.push_back("open fds after the resets past the warm-up: " + std::to_string(fd_min) +
                       ".." + std::to_string(fd_max) + " (flat wanted)");
  if (max_stall_s_ >= ping_interval_s)
    failures.push_back("the frame loop stalled " + std::to_string(max_stall_s_) + " s (" +
                       max_stall_state_ + ", simulated " + std::to_string(max_stall_at_s_) +
                       " s): the watchdog's ping interval is " + std::to_string(ping_interval_s) +
                       " s");
  if (kiosk_->idleResets() != long(resets_.size()) || long(resets_.size()) != visits_)
    failures.push_back(std::to_string(visits_) + " visits, " + std::to_string(resets_.size()) +
                       " resets seen, " + std::to_string(kiosk_->idleResets()) + " counted");
  if (strokes_mapped_ != strokes_fed_)
    failures.push_back(std::to_string(strokes_fed_) + " strokes replayed, " +
                       std::to_string(strokes_mapped_) + " mapped");
  std::printf(
      "kiosk_soak: %.2f simulated hours in %.0f s real, %ldx%d, grid %d: %ld visits, %ld idle "
      "resets, %ld strokes mapped of %ld replayed, %ld frames in %ld iterations\n",
      simS() / 3600.0, realS(), long(display.width()), display.height(), o_.grid, visits_,
      kiosk_->idleResets(), strokes_mapped_, strokes_fed_, frames_, iterations_);
  std::printf(
      "kiosk_soak: VmRSS after the last reset %.1f MB, median over the reference window (%zu "
      "resets, simulated %.0f-%.0f min) %.1f MB: %+.2f%% (within %.0f%% wanted)\n",
      final_kb / 1024.0, reference.size(), o_.warmup_minutes,
      o_.warmup_minutes + o_.reference_minutes, reference_kb / 1024.0, drift * 100.0,
      o_.rss_band_percent);
  std::printf("kiosk_soak: open fds after %zu resets past the warm-up: %d..%d\n", judged,
              judged ? fd_min : 0, judged ? fd_max : 0);
  std::printf(
      "kiosk_soak: longest frame-loop stall (real clock) %.2f s (%.2f s of process CPU; %s, "
      "simulated %.0f s); %ld iterations over 2 s; the most CPU one iteration took %.2f s; the "
      "watchdog pings every %.1f s\n",
      max_stall_s_, max_stall_cpu_s_, max_stall_state_.c_str(), max_stall_at_s_, stalls_over_2s_,
      max_cpu_s_, ping_interval_s);
  for (const std::string& f : failures) std::printf("kiosk_soak: FAILED: %s\n", f.c_str());
  std::printf(
      "{\"soak\":\"kiosk\",\"figures\":{\"simulated_hours\":%.3f,\"real_seconds\":%.0f,"
      "\"visits\":%ld,\"strokes\":%ld,\"frames\":%ld,\"final_rss_kb\":%ld,"
      "\"reference_rss_kb\":%.0f,\"rss_drift_percent\":%.3f,\"fds_min\":%d,\"fds_max\":%d,"
      "\"max_stall_s\":%.3f,\"max_stall_cpu_s\":%.3f,\"max_iteration_cpu_s\":%.3f,"
      "\"ping_interval_s\":%.1f,\"simulated_seconds\":%.0f}}\n",
      simS() / 3600.0, realS(), visits_, strokes_mapped_, frames_, long(final_kb), reference_kb,
      drift * 100.0, judged ? fd_min : 0, judged ? fd_max : 0, max_stall_s_, max_stall_cpu_s_,
      max_cpu_s_, ping_interval_s, simS());
  std::fflush(stdout);
  return failures.empty() ? 0 : 1;
}

int runKiosk(const SoakOptions& o) {
  // As `cloudbrush kiosk` does first (app/cli/command_paint.cpp).
  if (!setKioskHeapPolicy()) throw std::runtime_error("glibc refused the kiosk's heap settings");
  KioskParts parts = loadKioskParts();

  std::string error;
  DisplayOptions display_options;
  display_options.platform = DisplayPlatform::Surfaceless;
  display_options.width = o.width;
  display_options.height = o.height;
  std::unique_ptr<Display> display = openDisplay(display_options, &error);
  if (!display) throw std::runtime_error(error);
  VolumeRenderer renderer;
  if (!renderer.init(&error)) throw std::runtime_error(error);

  ManualClock clock(kSecond);
  VisitorPen pen(clock, parts.tablet);
  std::string watchdog_error;
  const std::optional<WatchdogTimeout> watchdog = watchdogTimeoutFromEnvironment(&watchdog_error);
  if (!watchdog) throw std::runtime_error("no watchdog asked for: " + watchdog_error);
  KioskService service(SdNotifier::fromEnvironment(), watchdog, clock, o.data_dir, &pen,
                       [](const std::string& problem) {
                         std::fprintf(stderr, "kiosk_soak: service: %s\n", problem.c_str());
                       });

  KioskSetup setup = parts.setup;
  setup.visitor_settings.screen_width = display->width();
  setup.visitor_settings.screen_height = display->height();
  setup.visitor_settings.grid = o.grid;
  setup.visitor_settings.auto_end_still_ms = parts.brush.stroke.auto_end_still_ms;
  setup.visitor_settings.auto_end_light_ms = parts.brush.stroke.auto_end_light_ms;
  setup.data_dir = o.data_dir;
  setup.on_status = [&service](const std::string& status) { service.onStatus(status); };
  setup.on_input = [&service]() { service.onInput(); };

  const Volume demo = makeBundledCumulus(glm::ivec3(o.grid), 1);
  PaintLoopOptions loop_options;
  loop_options.render = parts.render_config.options;
  loop_options.moving_scale = parts.render_config.moving_scale;
  loop_options.visitor_mode = true;
  loop_options.orbit_degrees_per_second = 0.0f;
  loop_options.config_dir = parts.config_dir;
  loop_options.state_dir = o.data_dir;
  loop_options.clock = &clock;
  std::unique_ptr<KioskScreen> kiosk;
  loop_options.before_start_again = [&kiosk]() { kiosk->keepFinishedCloud("start again"); };
  SoakDirector director(o, parts, clock, pen, service, renderer);
  loop_options.each_iteration = [&director](bool presented) { director.onIteration(presented); };

  PaintLoop loop(*display, renderer, demo, parts.render_config.light, loop_options);
  loop.attachPen(&pen, nullptr);
  kiosk = std::make_unique<KioskScreen>(*display, renderer, loop.screen(), &pen, clock,
                                        std::move(setup));
  director.watch(kiosk.get());
  PaintLoopSummary summary;
  const bool ran = loop.run(&g_stop, &summary, &error, kiosk.get());
  service.stopping();
  if (!ran) throw std::runtime_error(error);
  director.finish();
  const int verdict = director.judge(*display, double(watchdog->pingIntervalNs()) / 1e9);
  kiosk.reset();
  return verdict;
}

// ---- systemd's side and the trace (parent process) -------------------------------------------

std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

int runParent(int argc, char** argv, SoakOptions o) {
  const fs::path root = fs::temp_directory_path() / ("cb_kiosk_soak_" + std::to_string(::getpid()));
  fs::remove_all(root);
  fs::create_directories(root);
  const bool own_data_dir = o.data_dir.empty();
  if (own_data_dir) o.data_dir = (root / "data").string();
  o.data_dir = fs::absolute(o.data_dir).string();
  fs::create_directories(o.data_dir);
  const double watchdog_s = unitWatchdogSeconds();
  test::NotifySocketListener systemd;
  std::map<std::string, long> received;
  std::atomic<bool> done{false};
  std::thread receiver([&] {
    while (!done.load()) {
      const std::optional<std::string> m = systemd.receive(std::chrono::milliseconds(100));
      if (!m) continue;
      for (std::istringstream lines(*m); !lines.eof();) {
        std::string line;
        std::getline(lines, line);
        if (!line.empty()) ++received[line.substr(0, line.find('=') + 1)];
      }
    }
  });

  char self[4096];
  const ssize_t n = ::readlink("/proc/self/exe", self, sizeof self - 1);
  if (n <= 0) throw std::runtime_error("readlink /proc/self/exe failed");
  self[n] = '\0';
  std::string command = "NOTIFY_SOCKET=" + shellQuote(systemd.path()) +
                        " WATCHDOG_USEC=" + std::to_string(long(watchdog_s * 1e6)) +
                        " MESA_SHADER_CACHE_DIR=" + shellQuote(o.data_dir + "/mesa-shader-cache") +
                        " LIBGL_ALWAYS_SOFTWARE=1 CLOUDBRUSH_CONFIG_DIR=" +
                        shellQuote(std::string(CB_SOURCE_DIR) + "/config") + " ";
  const std::string trace = (root / "strace.txt").string();
  if (o.strace)
    command += "strace -f -qq --seccomp-bpf -e trace=%file -o " + shellQuote(trace) + " ";
  command += shellQuote(self);
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) != "--strace" && std::string(argv[i]) != "--data-dir")
      command += " " + shellQuote(argv[i]);
    else if (std::string(argv[i]) == "--data-dir")
      ++i;
  command += " --child --data-dir " + shellQuote(o.data_dir);
  FILE* child = ::popen(command.c_str(), "r");
  if (!child) throw std::runtime_error("cannot start " + command);
  std::string last_line;
  double simulated_s = 0.0;
  long visits = 0;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, child)) {
    std::fputs(buffer, stdout);
    std::fflush(stdout);
    last_line = buffer;
    if (const size_t k = last_line.find("\"simulated_seconds\":"); k != std::string::npos)
      simulated_s = std::atof(last_line.c_str() + k + 20);
    if (const size_t k = last_line.find("\"visits\":"); k != std::string::npos)
      visits = std::atol(last_line.c_str() + k + 9);
  }
  const int status = ::pclose(child);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  done.store(true);
  receiver.join();

  std::vector<std::string> failures;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    failures.push_back("the kiosk process failed (status " + std::to_string(status) + ")");
  // systemd's side: READY once, a STATUS at every screen change, WATCHDOG every ping interval.
  // A ping is due every half WatchdogSec of simulated time and goes out at the first loop
  // iteration after that: at most one clock step late.
  const double expected_pings = simulated_s / (watchdog_s / 2.0);
  const double fewest_pings =
      simulated_s / (watchdog_s / 2.0 + std::max(o.idle_step_s, o.stroke_step_s));
  std::printf(
      "kiosk_soak: NOTIFY_SOCKET received READY %ld, STATUS %ld (%ld visits), WATCHDOG %ld (%.0f "
      "simulated s: %.0f..%.0f due), STOPPING %ld\n",
      received["READY="], received["STATUS="], visits, received["WATCHDOG="], simulated_s,
      std::floor(fewest_pings), expected_pings, received["STOPPING="]);
  if (received["READY="] != 1) failures.push_back("READY=1 not received exactly once");
  if (received["STOPPING="] != 1) failures.push_back("STOPPING=1 not received exactly once");
  // With READY, then "visitor N painting" and "attract loop" for every visit.
  if (received["STATUS="] < 1 + 2 * visits)
    failures.push_back("fewer STATUS= messages than screen changes");
  if (simulated_s <= 0.0 || double(received["WATCHDOG="]) < std::floor(fewest_pings) ||
      double(received["WATCHDOG="]) > expected_pings + 2.0)
    failures.push_back("WATCHDOG=1 pings do not match one per ping interval");
  if (o.strace) {
    std::ifstream in(trace);
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    const test::FileWrites writes =
        test::fileWritesOutside(text, fs::current_path().string(), {o.data_dir});
    std::printf("kiosk_soak: strace -f -e trace=%%file: %zu writing calls, %zu outside %s\n",
                writes.writes, writes.outside.size(), o.data_dir.c_str());
    for (size_t i = 0; i < writes.outside.size() && i < 10; ++i)
      std::printf("kiosk_soak:   outside: %s\n", writes.outside[i].c_str());
    if (writes.writes < 10) failures.push_back("strace saw too few writes (is it tracing?)");
    if (!writes.outside.empty()) failures.push_back("files written outside the data dir");
  }
  for (const std::string& f : failures) std::printf("kiosk_soak: FAILED: %s\n", f.c_str());
  std::printf("kiosk_soak: %s\n", failures.empty() ? "PASSED" : "FAILED");
  if (failures.empty()) {
    fs::remove_all(root);
    if (!own_data_dir) fs::remove_all(o.data_dir);
  } else {
    std::printf("kiosk_soak: kept %s for looking\n", root.c_str());
  }
  return failures.empty() ? 0 : 1;
}

}  // namespace
}  // namespace cb

int main(int argc, char** argv) {
  cb::SoakOptions options;
  if (!cb::parseArgs(argc, argv, &options)) return 2;
  return cb::test::runReportingErrors("kiosk_soak", [&] {
    if (options.child) {
      std::signal(SIGTERM, [](int) { cb::g_stop.store(true); });
      return cb::runKiosk(options);
    }
    return cb::runParent(argc, argv, options);
  });
}
