// A month on the plinth: 30 days of 12 opening hours compressed by driving the kiosk headless
// from the injectable clock, with its data dir on a REAL small file system (a size-limited tmpfs,
// needs root) that something else fills half-way through the month and that gets space back
// later. The real parts as `cloudbrush kiosk` wires them — EGL surfaceless on llvmpipe, the
// bundled config with the gallery on (as an installer turns it on), the bundled attract journal,
// the shell's frame loop running KioskScreen over the painter, KioskService (health.json and the
// metrics file for node_exporter) — on a ManualClock the director below moves on after every loop
// iteration. Visitors paint synthetic pen strokes (random curves at 200 Hz with a pressure swell,
// seeded) and walk away; the product's idle countdown ends each visit and keeps the cloud.
//
// Checked (exit status 1 and a FAILED line when not):
//   - every visitor's cloud is either a complete gallery entry, or the loss is said: the kiosk
//     counts a failed save, the operator panel (opened with the key combination and the PIN
//     right after the visit) shows the disk line in its failed state, and health.json and the
//     metrics file, read before the next visitor, carry the same counts, storage not ok and a
//     last_error; a visit lost without all of these is a silent loss, and there must be none;
//   - the fill really made saves fail (else nothing was tested), and after space returns the
//     kiosk saves again by itself: every visit from the first day after the space returned on
//     is saved;
//   - VmRSS, sampled after every idle reset once the next visitor's session is made: the median
//     of the last day within --rss-band-percent (the 2 %) of the median of day 2 (day 1
//     warms the shader cache and the allocator);
//   - no crash: the loop ran to the end (an exception or a signal fails the ctest).
//
//   build/tests/unit/kiosk/kiosk_month              # the month (ctest -L slow -R kiosk_month)
//   build/tests/unit/kiosk/kiosk_month --days 3 --fill-day 2 --free-day 3   # a quick look
// The seed is CB_TEST_SEED when set (else 1) and is printed.
#include <sys/mount.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "app/brush/brush_config.h"
#include "app/core/config_paths.h"
#include "app/kiosk/kiosk_config.h"
#include "app/kiosk/kiosk_heap.h"
#include "app/kiosk/kiosk_service.h"
#include "app/kiosk/kiosk_texts.h"
#include "app/kiosk/operator_pin.h"
#include "app/mapping/mapping_config.h"
#include "app/render/gl/display.h"
#include "app/render/image_io.h"
#include "app/render/render_config.h"
#include "app/render/volume_renderer.h"
#include "app/session/synthetic_session.h"
#include "app/shell/kiosk/kiosk_screen.h"
#include "app/shell/painter/paint_loop.h"
#include "app/volume/volume.h"
#include "drivers/core/clock.h"
#include "drivers/core/journal.h"
#include "drivers/core/pen_source.h"
#include "small_tmpfs.h"
#include "tests/support/command_line.h"

namespace cb {
namespace {

namespace fs = std::filesystem;
constexpr int64_t kSecond = 1'000'000'000;
constexpr int64_t kDay = 86400 * kSecond;
const std::string kPin = "2468";

struct MonthOptions {
  int days = 30;
  double open_hours = 12.0;   // visitors from 09:00 for this long; the attract loop all night
  int visitors_per_day = 8;   // at random times within the opening hours
  int strokes_per_visit = 3;  // short visits: the month is about the disk and the memory
  int width = 640, height = 360;
  int grid = 64;
  uint64_t disk_bytes = 32ull << 20;  // the tmpfs the data dir is on
  uint64_t floor_bytes = 8ull << 20;  // gallery.min_free_mb
  // From this day's opening another writer on the disk (a runaway log) takes every byte there is,
  // again before every visitor, so what the kiosk frees is gone again ...
  int fill_day = 15;
  // ... until this day's opening, when it stops and gives this much back.
  int free_day = 20;
  uint64_t freed_bytes = 24ull << 20;
  // The bound between day 2 and the last day, either way.
  double rss_band_percent = 2.0;
  uint32_t seed = 1;
};

// The options, or false after saying what is wrong on stderr.
bool parseArgs(int argc, char** argv, MonthOptions* o) {
  const auto integer = [](int* field) {
    return [field](const std::string& v) { *field = std::stoi(v); };
  };
  const auto megabytes = [](uint64_t* field) {
    return [field](const std::string& v) { *field = std::stoull(v) << 20; };
  };
  const std::vector<test::CommandOption> options = {
      {"--days", integer(&o->days)},
      {"--visitors-per-day", integer(&o->visitors_per_day)},
      {"--strokes-per-visit", integer(&o->strokes_per_visit)},
      {"--grid", integer(&o->grid)},
      {"--disk-mb", megabytes(&o->disk_bytes)},
      {"--floor-mb", megabytes(&o->floor_bytes)},
      {"--fill-day", integer(&o->fill_day)},
      {"--free-day", integer(&o->free_day)},
      {"--freed-mb", megabytes(&o->freed_bytes)},
      {"--rss-band-percent", [o](const std::string& v) { o->rss_band_percent = std::stod(v); }},
      {"--size",
       [o](const std::string& v) { test::parseSizeOption("--size", v, &o->width, &o->height); }},
  };
  if (!test::parseCommandLine("kiosk_month", argc, argv, options)) return false;
  if (const char* seed = std::getenv("CB_TEST_SEED")) o->seed = uint32_t(std::stoul(seed));
  if (o->days < 3 || o->visitors_per_day < 1 || o->strokes_per_visit < 1 || o->fill_day < 2 ||
      o->free_day <= o->fill_day || o->free_day > o->days) {
    std::fprintf(stderr,
                 "kiosk_month: bad values (days >= 3, 2 <= fill day < free day <= days, "
                 "visitors >= 1)\n");
    return false;
  }
  return true;
}

// ---- the visitors ----------------------------------------------------------------------------

// A tablet whose samples come out when the clock reaches their time stamps.
class TimedPen final : public PenSource {
 public:
  TimedPen(const Clock& clock, PenDeviceInfo info) : clock_(clock), info_(std::move(info)) {}
  const char* backendName() const override { return "synthetic visitors"; }
  void poll(int, std::vector<PenSample>& out) override {
    for (; next_ < samples_.size() && samples_[next_].t_ns <= clock_.nowNs(); ++next_)
      out.push_back(samples_[next_]);
  }
  PenConnection connection() const override { return PenConnection::kConnected; }
  const PenDeviceInfo& deviceInfo() const override { return info_; }
  std::string statusMessage() const override { return "synthetic visitors"; }
  void play(std::vector<PenSample> samples) {
    samples_ = std::move(samples);
    next_ = 0;
  }
  bool done() const { return next_ >= samples_.size(); }

 private:
  const Clock& clock_;
  PenDeviceInfo info_;
  std::vector<PenSample> samples_;
  size_t next_ = 0;
};

// `strokes` random curves across the middle of the screen, each with a pressure swell, 0.5–2 s
// apart, at 200 Hz from `t0_ns`.
std::vector<PenSample> visitSamples(std::mt19937& rng, const PenDeviceInfo& tablet, int w, int h,
                                    int strokes, int64_t t0_ns) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<PenSample> samples;
  int64_t t = t0_ns;
  for (int k = 0; k < strokes; ++k) {
    SyntheticStroke s;
    const float y = float(h) * (0.3f + 0.4f * unit(rng));
    const float x0 = float(w) * (0.15f + 0.2f * unit(rng));
    const float x1 = float(w) * (0.65f + 0.2f * unit(rng));
    s.control_points = {{x0, y},
                        {0.5f * (x0 + x1), y + float(h) * (unit(rng) - 0.5f) * 0.3f},
                        {x1, y + float(h) * (unit(rng) - 0.5f) * 0.2f}};
    const float peak = 0.5f + 0.45f * unit(rng);
    s.pressure = [peak](float a) { return 0.2f + (peak - 0.2f) * 4.0f * a * (1.0f - a); };
    s.speed_px_s = float(w) * (0.4f + 0.4f * unit(rng));
    const std::vector<PenSample> stroke = syntheticPenSamples(s, tablet, w, h, 200.0, t);
    samples.insert(samples.end(), stroke.begin(), stroke.end());
    t = samples.back().t_ns + int64_t((0.5 + 1.5 * unit(rng)) * 1e9);
  }
  return samples;
}

// ---- what the operator and the fleet see -----------------------------------------------------

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// A number after `"key":` in health.json's one line (-1 when absent).
long jsonLong(const std::string& json, const std::string& key) {
  const size_t k = json.find("\"" + key + "\":");
  return k == std::string::npos ? -1 : std::atol(json.c_str() + k + key.size() + 3);
}

std::string jsonText(const std::string& json, const std::string& key) {
  const size_t k = json.find("\"" + key + "\":");
  if (k == std::string::npos) return "";
  const size_t v = k + key.size() + 3;
  if (json.compare(v, 4, "null") == 0) return "null";
  const size_t end = json.find("\",\"", v + 1);
  return json.substr(v + 1, end == std::string::npos ? std::string::npos : end - v - 1);
}

// A sample's value in the Prometheus text (-1 when absent).
double metric(const std::string& text, const std::string& name) {
  const size_t k = text.find("\n" + name + " ");
  return k == std::string::npos ? -1.0 : std::atof(text.c_str() + k + name.size() + 2);
}

long vmRssKb() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// ---- the month -------------------------------------------------------------------------------

struct DayFigures {
  long visits = 0, saved = 0, lost_said = 0, lost_silent = 0, saves_failed = 0;
  std::vector<double> rss_kb;  // after every idle reset
  double free_mb = 0.0;        // at the day's last reset
  long gallery_entries = 0;
};

// What one visit left, judged before the next visitor comes.
struct VisitOutcome {
  long saved_before = 0, failed_before = 0;
  bool panel_open = false, panel_said = false;
  int64_t reset_ns = 0;
};

class MonthRun {
 public:
  MonthRun(const MonthOptions& o, std::string root) : o_(o), root_(std::move(root)) {}
  int run();

 private:
  enum class Phase { kWaiting, kVisiting, kLeft, kReset, kPanel, kPanelClosing, kJudging };
  void setUp();
  void onIteration();
  void startDay();
  void beginVisit(int64_t now);
  void afterReset(int64_t now);
  void judgeVisit();
  bool savedCompletely(long before) const;
  int finish(bool ran, const std::string& error);
  // The frame last drawn, as a PNG under $CB_KEEP_FRAMES (when set), once per name.
  void keepFrame(const std::string& name);
  int day() const { return int(clock_.nowNs() / kDay) + 1; }
  int64_t opening(int d) const { return int64_t(d - 1) * kDay + 9 * 3600 * kSecond; }

  MonthOptions o_;
  std::string root_, data_dir_, metrics_dir_;
  std::unique_ptr<test::SmallTmpfs> disk_;
  ManualClock clock_{kSecond};
  std::unique_ptr<Display> display_;
  VolumeRenderer renderer_;
  std::unique_ptr<TimedPen> pen_;
  std::unique_ptr<KioskService> service_;
  std::unique_ptr<KioskScreen> kiosk_;
  std::atomic<bool> stop_{false};
  std::mt19937 rng_;
  Phase phase_ = Phase::kWaiting;
  std::vector<int64_t> schedule_;  // today's visitors, arriving
  size_t next_visitor_ = 0;
  int scheduled_day_ = 0;
  VisitOutcome visit_;
  std::map<int, DayFigures> days_;
  std::vector<std::string> failures_, problems_;
  long visits_ = 0;
  bool filled_ = false, freed_ = false;
  int64_t freed_ns_ = -1;
  long visits_after_free_ = 0, saved_after_free_ = 0;
  const std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
  std::vector<std::string> kept_frames_;
};

void MonthRun::keepFrame(const std::string& name) {
  const char* dir = std::getenv("CB_KEEP_FRAMES");
  if (!dir || std::find(kept_frames_.begin(), kept_frames_.end(), name) != kept_frames_.end())
    return;
  kept_frames_.push_back(name);
  writePng(std::string(dir) + "/" + name,
           readFramebufferRgba8(display_->framebuffer(), display_->width(), display_->height()));
}

void MonthRun::setUp() {
  if (!setKioskHeapPolicy()) throw std::runtime_error("glibc refused the kiosk's heap settings");
  disk_ = std::make_unique<test::SmallTmpfs>(root_ + "/disk", o_.disk_bytes);
  if (!disk_->mounted()) throw std::runtime_error(disk_->why());
  data_dir_ = root_ + "/disk/cloudbrush";
  metrics_dir_ = root_ + "/node-exporter";  // node_exporter's textfile folder, another disk
  fs::create_directories(data_dir_);
  fs::create_directories(metrics_dir_);
  ::setenv("MESA_SHADER_CACHE_DIR", (root_ + "/mesa-shader-cache").c_str(), 1);
  std::string error;
  if (!OperatorPinGuard(data_dir_).setPin(kPin, &error)) throw std::runtime_error(error);
  DisplayOptions display_options;
  display_options.platform = DisplayPlatform::Surfaceless;
  display_options.width = o_.width;
  display_options.height = o_.height;
  display_ = openDisplay(display_options, &error);
  if (!display_) throw std::runtime_error(error);
  if (!renderer_.init(&error)) throw std::runtime_error(error);
  pen_ = std::make_unique<TimedPen>(clock_, syntheticTablet(o_.width, o_.height));
  service_ =
      std::make_unique<KioskService>(SdNotifier::fromEnvironment(), std::nullopt, clock_, data_dir_,
                                     pen_.get(), [](const std::string& problem) {
                                       std::fprintf(stderr, "kiosk_month: %s\n", problem.c_str());
                                     });
  service_->setMetricsDir(metrics_dir_);
  rng_.seed(o_.seed);
}

int MonthRun::run() {
  setUp();
  const std::string config_dir = defaultConfigDir();
  const auto path = [&](const std::string& name) { return config_dir + "/" + name; };
  const RenderConfig render_config = loadRenderConfig(path("render.toml"));
  KioskSetup setup;
  setup.config = loadKioskConfig(path("kiosk.toml"));
  setup.config.gallery_enabled = true;  // as an installer turns it on (README)
  setup.config.min_free_bytes = o_.floor_bytes;
  setup.config.metrics_dir = metrics_dir_;
  setup.texts =
      KioskTexts::load(path("kiosk/texts.toml"), setup.config.language, [](const std::string&) {});
  JournalReadResult attract = readJournal(path(setup.config.attract_journal));
  if (!attract.error.empty()) throw std::runtime_error("attract journal: " + attract.error);
  setup.attract_journal = std::move(attract.records);
  setup.data_dir = data_dir_;
  setup.config_dir = config_dir;
  const BrushConfig brush = loadDefaultBrushConfig();
  setup.visitor_settings.screen_width = o_.width;
  setup.visitor_settings.screen_height = o_.height;
  setup.visitor_settings.grid = o_.grid;
  setup.visitor_settings.auto_end_still_ms = brush.stroke.auto_end_still_ms;
  setup.visitor_settings.auto_end_light_ms = brush.stroke.auto_end_light_ms;
  setup.brush = brush;
  setup.mapping = loadMappingConfig(path("mapping.toml"));
  setup.light = render_config.light;
  setup.style = renderStyleName(render_config.options.style);
  setup.render = render_config.options;
  setup.render_settings = formatRenderConfig(render_config);
  setup.moving_scale = render_config.moving_scale;
  setup.on_status = [this](const std::string& status) { service_->onStatus(status); };
  setup.on_input = [this]() { service_->onInput(); };
  setup.on_problem = [this](const std::string& problem) {
    problems_.push_back(problem);
    service_->onProblem(problem);
  };
  setup.on_storage = [this](const std::string& problem) { service_->onStorage(problem); };

  const Volume empty(glm::ivec3(8));
  PaintLoopOptions loop_options;
  loop_options.render = render_config.options;
  loop_options.moving_scale = render_config.moving_scale;
  loop_options.visitor_mode = true;
  loop_options.orbit_degrees_per_second = 0.0f;
  loop_options.config_dir = config_dir;
  loop_options.state_dir = data_dir_;
  loop_options.clock = &clock_;
  loop_options.before_start_again = [this]() { kiosk_->keepFinishedCloud("start again"); };
  loop_options.each_iteration = [this](bool presented) {
    service_->setCounts(kiosk_->counts());
    service_->onIteration(presented);
    onIteration();
  };
  PaintLoop loop(*display_, renderer_, empty, render_config.light, loop_options);
  loop.attachPen(pen_.get(), nullptr);
  kiosk_ = std::make_unique<KioskScreen>(*display_, renderer_, loop.screen(), pen_.get(), clock_,
                                         std::move(setup));
  PaintLoopSummary summary;
  std::string error;
  const bool ran = loop.run(&stop_, &summary, &error, kiosk_.get());
  service_->stopping();
  return finish(ran, error);
}

// Today's visitors at random times within the opening hours (sorted; a visitor who arrives while
// another paints waits); the disk filled or given space back at the opening.
void MonthRun::startDay() {
  if (const auto last = days_.find(scheduled_day_); last != days_.end()) {
    const DayFigures& f = last->second;
    std::printf(
        "kiosk_month: day %d done (real %.0f s): %ld visits, %ld saved, %ld lost and said, "
        "%ld lost silently, VmRSS median %.1f MB, %.1f MB free\n",
        scheduled_day_,
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count(),
        f.visits, f.saved, f.lost_said, f.lost_silent, median(f.rss_kb) / 1024.0, f.free_mb);
  }
  scheduled_day_ = day();
  schedule_.clear();
  next_visitor_ = 0;
  std::uniform_real_distribution<double> within(0.0, o_.open_hours * 3600.0 - 600.0);
  for (int i = 0; i < o_.visitors_per_day; ++i)
    schedule_.push_back(opening(scheduled_day_) + int64_t(within(rng_) * 1e9));
  std::sort(schedule_.begin(), schedule_.end());
  if (scheduled_day_ == o_.fill_day && !filled_) {
    const uint64_t bytes = disk_->fillLeaving(0, root_ + "/disk/other-service.log");
    std::printf(
        "kiosk_month: day %d: another writer filled the disk (%.1f MB written, %.2f MB "
        "free) and keeps it full\n",
        scheduled_day_, double(bytes) / 1048576.0, double(disk_->freeBytes()) / 1048576.0);
    filled_ = true;
  }
  if (scheduled_day_ == o_.free_day && !freed_) {
    const std::string filler = root_ + "/disk/other-service.log";
    const uintmax_t size = fs::file_size(filler);
    fs::resize_file(filler, size > o_.freed_bytes ? size - o_.freed_bytes : 0);
    std::printf(
        "kiosk_month: day %d: the other writer stopped and gave back %.1f MB (%.1f MB free)\n",
        scheduled_day_, double(o_.freed_bytes) / 1048576.0, double(disk_->freeBytes()) / 1048576.0);
    freed_ = true;
    freed_ns_ = clock_.nowNs();
  }
  std::fflush(stdout);
}

void MonthRun::beginVisit(int64_t now) {
  if (filled_ && !freed_) disk_->fillLeaving(0, root_ + "/disk/other-service.log");
  visit_ = VisitOutcome{};
  visit_.saved_before = long(kiosk_->gallerySaved().size());
  visit_.failed_before = kiosk_->savesFailed();
  pen_->play(
      visitSamples(rng_, pen_->deviceInfo(), o_.width, o_.height, o_.strokes_per_visit, now));
  ++visits_;
  ++days_[day()].visits;
  phase_ = Phase::kVisiting;
}

void MonthRun::onIteration() {
  const int64_t now = clock_.nowNs();
  const KioskScreen::State state = kiosk_->state();
  double step_s = 1.0;
  switch (phase_) {
    case Phase::kWaiting: {
      const int d = day();
      if (scheduled_day_ < d && now >= opening(d)) startDay();
      if (scheduled_day_ == d && next_visitor_ < schedule_.size()) {
        if (now >= schedule_[next_visitor_]) {
          ++next_visitor_;
          beginVisit(now);
          step_s = 0.1;
          break;
        }
        step_s = std::clamp(double(schedule_[next_visitor_] - now) / 1e9, 1.0, 300.0);
        break;
      }
      if (scheduled_day_ >= o_.days) {  // the last visitor of the month is judged
        stop_.store(true);
        break;
      }
      const int64_t next = opening(scheduled_day_ == d ? d + 1 : d);
      step_s = std::clamp(double(next - now) / 1e9, 1.0, 3600.0);  // the attract loop all night
      break;
    }
    case Phase::kVisiting:
      step_s = 0.25;  // the pen's samples come at 200 Hz; the loop takes them 50 at a time
      if (pen_->done()) phase_ = Phase::kLeft;
      break;
    case Phase::kLeft:  // the visitor walked away: the idle countdown (the product's times)
      step_s = 5.0;
      if (state == KioskScreen::State::kAttract) {
        visit_.reset_ns = now;
        phase_ = Phase::kReset;
        step_s = 0.1;
      }
      break;
    case Phase::kReset:
      step_s = 0.5;
      if (kiosk_->nextVisitorReady()) afterReset(now);
      break;
    case Phase::kPanel:
      step_s = 0.5;
      if (state == KioskScreen::State::kOperator && kiosk_->operatorPanel().unlocked()) {
        const OperatorPanelValues& values = kiosk_->operatorPanel().values();
        visit_.panel_open = true;
        visit_.panel_said = !values.storage_ok && values.storage.find("NOT SAVING") == 0;
        keepFrame("kiosk_month_panel_disk_full.png");
        kiosk_->onKey(DisplayEvent::key(0xff1b), now);  // Esc
        phase_ = Phase::kPanelClosing;
      } else if (now - visit_.reset_ns > 30 * kSecond) {
        phase_ = Phase::kJudging;  // never opened: judged as not said
      }
      break;
    case Phase::kPanelClosing:
      step_s = 0.5;
      if (state == KioskScreen::State::kAttract) phase_ = Phase::kJudging;
      break;
    case Phase::kJudging:
      // Two health intervals after the reset (5 s each): the files carry this visit.
      step_s = 1.0;
      if (now - visit_.reset_ns >= 12 * kSecond) {
        judgeVisit();
        phase_ = Phase::kWaiting;
      }
      break;
  }
  clock_.advance(int64_t(step_s * 1e9));
}

// The reset is complete (the next visitor's session made): VmRSS, and when this visitor's cloud
// did not reach the gallery, the operator opens the panel to look at the disk line.
void MonthRun::afterReset(int64_t now) {
  days_[day()].rss_kb.push_back(double(vmRssKb()));
  if (long(kiosk_->gallerySaved().size()) > visit_.saved_before) {
    phase_ = Phase::kJudging;
    return;
  }
  kiosk_->onKey(DisplayEvent::key('o', DisplayEvent::kCtrl | DisplayEvent::kAlt), now);
  for (char c : kPin) kiosk_->onKey(DisplayEvent::key(uint32_t(c)), now);
  kiosk_->onKey(DisplayEvent::key(0xff0d), now);  // Enter
  phase_ = Phase::kPanel;
}

bool MonthRun::savedCompletely(long before) const {
  const std::vector<long>& saved = kiosk_->gallerySaved();
  if (long(saved.size()) != before + 1) return false;
  char name[16];
  std::snprintf(name, sizeof name, "%06ld", saved.back());
  const std::string entry = data_dir_ + "/gallery/" + name;
  for (const char* file :
       {"cloud.vdb", "cloud.cbvol", "render.exr", "render.png", "thumbnail.png"}) {
    std::error_code ec;
    if (fs::file_size(entry + "/" + file, ec) == 0 || ec) return false;
  }
  return true;
}

// Saved completely, or lost and said everywhere the operator and the fleet look.
void MonthRun::judgeVisit() {
  DayFigures& f = days_[day()];
  const long saved_now = long(kiosk_->gallerySaved().size());
  const long failed_now = kiosk_->savesFailed();
  const std::string health = slurp(data_dir_ + "/health.json");
  const std::string metrics = "\n" + slurp(metrics_dir_ + "/cloudbrush.prom");
  const bool health_agrees = jsonLong(health, "visits") == kiosk_->visits() &&
                             jsonLong(health, "gallery_saved") == saved_now &&
                             jsonLong(health, "saves_failed") == failed_now;
  const bool metrics_agree =
      metric(metrics, "cloudbrush_visits_total") == double(visits_) &&
      metric(metrics, "cloudbrush_gallery_saved_total") == double(saved_now) &&
      metric(metrics, "cloudbrush_saves_failed_total") == double(failed_now);
  const std::string where = "day " + std::to_string(day()) + ", visit " + std::to_string(visits_);
  if (!health_agrees || !metrics_agree)
    failures_.push_back(where + ": health.json or the metrics do not carry the kiosk's counts");
  f.saves_failed += failed_now - visit_.failed_before;
  f.free_mb = double(disk_->freeBytes()) / 1048576.0;
  std::error_code ec;
  f.gallery_entries = 0;
  for (const auto& e : fs::directory_iterator(data_dir_ + "/gallery", ec))
    f.gallery_entries += e.is_directory() && e.path().filename().string()[0] != '.';
  if (freed_) ++visits_after_free_;
  if (savedCompletely(visit_.saved_before)) {
    ++f.saved;
    if (freed_) ++saved_after_free_;
    return;
  }
  const bool said = failed_now > visit_.failed_before && visit_.panel_said && health_agrees &&
                    metrics_agree && jsonText(health, "storage") != "ok" &&
                    jsonText(health, "last_error") != "null" &&
                    metric(metrics, "cloudbrush_storage_ok") == 0.0;
  if (said) {
    ++f.lost_said;
    return;
  }
  ++f.lost_silent;
  failures_.push_back(where + ": the cloud was lost without saying so (saves failed " +
                      std::to_string(visit_.failed_before) + " -> " + std::to_string(failed_now) +
                      ", panel " + (visit_.panel_open ? "open" : "never opened") + ", said " +
                      (visit_.panel_said ? "yes" : "no") + ", health.json " + health + ")");
}

int MonthRun::finish(bool ran, const std::string& error) {
  if (!ran) failures_.push_back("the frame loop failed: " + error);
  long visits = 0, saved = 0, said = 0, silent = 0, failed = 0, lost_before_fill = 0;
  std::printf(
      "kiosk_month: day  visits  saved  lost(said)  lost(silent)  saves_failed  "
      "VmRSS_MB(median)  free_MB  gallery_entries\n");
  for (const auto& [d, f] : days_) {
    visits += f.visits, saved += f.saved, said += f.lost_said, silent += f.lost_silent;
    failed += f.saves_failed;
    if (d < o_.fill_day) lost_before_fill += f.lost_said + f.lost_silent;
    std::printf("kiosk_month: %3d  %6ld  %5ld  %10ld  %12ld  %12ld  %16.1f  %7.1f  %15ld\n", d,
                f.visits, f.saved, f.lost_said, f.lost_silent, f.saves_failed,
                median(f.rss_kb) / 1024.0, f.free_mb, f.gallery_entries);
  }
  const double day2 = median(days_[2].rss_kb), last = median(days_[o_.days].rss_kb);
  const double drift = day2 > 0.0 ? (last - day2) / day2 * 100.0 : 100.0;
  if (std::abs(drift) > o_.rss_band_percent)
    failures_.push_back("VmRSS median of day " + std::to_string(o_.days) + " is " +
                        std::to_string(drift) + " % off day 2's (within " +
                        std::to_string(o_.rss_band_percent) + " % wanted)");
  if (said + silent == 0) failures_.push_back("the full disk never made a save fail");
  if (lost_before_fill > 0)
    failures_.push_back(std::to_string(lost_before_fill) +
                        " clouds lost before the disk was filled (the floor should hold)");
  if (visits_after_free_ == 0 || saved_after_free_ != visits_after_free_)
    failures_.push_back("after space returned " + std::to_string(saved_after_free_) + " of " +
                        std::to_string(visits_after_free_) + " visits saved (all wanted)");
  if (visits != visits_ || kiosk_->idleResets() != visits_)
    failures_.push_back(std::to_string(visits_) + " visitors, " + std::to_string(visits) +
                        " judged, " + std::to_string(kiosk_->idleResets()) + " idle resets");
  std::printf(
      "kiosk_month: %d days x %.0f h: %ld visits, %ld saved, %ld lost and said (operator "
      "panel, health.json, metrics), %ld lost silently, %ld saves failed (journals and gallery "
      "entries); %ld saved after space returned of %ld; VmRSS day 2 %.1f MB, day %d %.1f MB: "
      "%+.2f %% (within %.0f %%); seed %u\n",
      o_.days, o_.open_hours, visits, saved, said, silent, failed, saved_after_free_,
      visits_after_free_, day2 / 1024.0, o_.days, last / 1024.0, drift, o_.rss_band_percent,
      o_.seed);
  for (const std::string& f : failures_) std::printf("kiosk_month: FAILED: %s\n", f.c_str());
  std::printf(
      "{\"soak\":\"kiosk_month\",\"figures\":{\"days\":%d,\"visits\":%ld,\"saved\":%ld,"
      "\"lost_said\":%ld,\"lost_silent\":%ld,\"saves_failed\":%ld,\"rss_day2_kb\":%.0f,"
      "\"rss_last_kb\":%.0f,\"rss_drift_percent\":%.3f,\"seed\":%u}}\n",
      o_.days, visits, saved, said, silent, failed, day2, last, drift, o_.seed);
  std::printf("kiosk_month: %s\n", failures_.empty() ? "PASSED" : "FAILED");
  std::fflush(stdout);
  kiosk_.reset();
  return failures_.empty() ? 0 : 1;
}

}  // namespace
}  // namespace cb

int main(int argc, char** argv) {
  cb::MonthOptions options;
  if (!cb::parseArgs(argc, argv, &options)) return 2;
  if (::geteuid() != 0) {
    std::printf("kiosk_month: SKIPPED: needs root to mount a tmpfs as the data dir's disk\n");
    return 77;
  }
  std::printf("kiosk_month: seed %u (CB_TEST_SEED), %d days, %d visitors a day\n", options.seed,
              options.days, options.visitors_per_day);
  const std::string root =
      (std::filesystem::temp_directory_path() / ("cb_kiosk_month_" + std::to_string(::getpid())))
          .string();
  std::filesystem::create_directories(root);
  const int status = cb::test::runReportingErrors("kiosk_month", [&] {
    cb::MonthRun run(options, root);
    return run.run();
  });
  std::error_code ec;
  std::filesystem::remove_all(root, ec);
  return status;
}
