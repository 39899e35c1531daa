// `cloudbrush bench latency`: pen sample → frame ready and → present while painting (the
// product's loop, PaintLoop on EGL surfaceless at 1920×1080 by default) over the bundled
// cumulus in the default sky. The pen is the replay source at 200 Hz on its real time line: each
// sample plays when its time comes and is stamped with that time (ReplayOptions::restamp), as a
// tablet's kernel timestamp is the report's time; the clock starts there. Strokes follow each
// other --gap-ms apart, so the next one is drawn while the previous stroke's cloud is refined
// to full resolution. Every figure comes from the session's own Frame records
// (drivers/core/journal_frame.h), as `replay --stats` reads them.
//
// The baseline, measured in the same process and run first, is the loop before late latching
// (PaintLoopOptions::ink_first = false: samples read once per frame before the scene's work; a
// refinement cast whole). Between it and the product runs the ink first with its samples
// latched once, before the composite (late_ink = false), reported as `early_*` figures; the
// product then draws the ink last, from samples latched after the frame was made. Offscreen,
// "present" is the glFinish after the frame, so sample → present is sample → ready plus the finish;
// there is no refresh to wait for. Never fails on a missed target.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "app/bench/bench_report.h"
#include "app/bench/benches.h"
#include "app/cli/args.h"
#include "app/core/parallel_for.h"
#include "app/render/gl/display.h"
#include "app/render/volume_renderer.h"
#include "app/session/paint_session.h"
#include "app/session/synthetic_session.h"
#include "app/shell/painter/paint_loop.h"
#include "app/study/frame_timing_stats.h"
#include "app/volume/scene_generators.h"
#include "app/volume/sky_extent.h"
#include "drivers/core/clock.h"
#include "drivers/replay/replay_pen_source.h"

namespace cb {
namespace {

const char kHelp[] =
    "usage: cloudbrush bench latency [--size WxH] [--strokes N] [--gap-ms MS] [--grid N]\n"
    "  Runs the baseline (the loop before late latching), the ink first latched once before the\n"
    "  composite, and the product (the ink last), in that order, in one process.\n"
    "  --size WxH     screen (default 1920x1080)\n"
    "  --strokes N    strokes of a 200 Hz pen (default 6)\n"
    "  --gap-ms MS    pen up between strokes (default 250: the next stroke is drawn while the\n"
    "                 last one's cloud is refined)\n"
    "  --grid N       home box N^3 (default 256, the painter's)\n"
    "Target on 2 cores, llvmpipe, 1920x1080: sample -> frame ready p95 <= 8 ms, p99 <= 16.7 ms\n"
    "(the ink frames; the lift frames, the pen-up wait, are reported apart).\n";

// Hovering before the first stroke: the painter stops its orbit at the pen's first sample and
// casts the paint view at full resolution once (seconds on llvmpipe), before any ink.
constexpr double kLeadInMs = 3000.0;

// The reference strokes as raw samples of the synthetic tablet at 200 Hz, `gap_ms` apart, after
// kLeadInMs of hovering where the first one begins.
std::string writePenJournal(const std::string& path, int w, int h, int strokes, double gap_ms) {
  JournalWriter journal;
  if (!journal.open(path)) return journal.error();
  const PenDeviceInfo tablet = syntheticTablet(w, h);
  const std::vector<uint8_t> device = encodeDeviceInfo(tablet);
  journal.append(JournalRecordType::kDevice, 0, device.data(), device.size());
  const std::vector<SyntheticStroke> reference = referencePaintStrokes(w, h);
  int64_t t0 = 1'000'000'000;
  const PenSample hover = syntheticPenSamples(reference.front(), tablet, w, h, 200.0, t0).front();
  for (int64_t t = 0; t < int64_t(kLeadInMs * 1e6); t += 5'000'000) {
    PenSample s = hover;
    s.t_ns = t0 + t;
    journal.appendPenSample(s);
  }
  t0 += int64_t(kLeadInMs * 1e6);
  for (int i = 0; i < strokes; ++i) {
    const std::vector<PenSample> samples =
        syntheticPenSamples(reference[size_t(i) % reference.size()], tablet, w, h, 200.0, t0);
    for (const PenSample& s : samples) journal.appendPenSample(s);
    t0 = samples.back().t_ns + int64_t(gap_ms * 1e6);
  }
  journal.close();
  return "";
}

// The replayed pen held back until the painter has presented its first frames (llvmpipe compiles
// its shaders then: seconds), then played from its start on its real time line; notes when the
// first tip-down sample played, so the figures leave out the lead-in's hover.
class HeldPen final : public PenSource {
 public:
  explicit HeldPen(ReplayPenSource& pen) : pen_(pen) {}
  void release() { released_ = true; }
  int64_t firstContactNs() const { return first_contact_ns_; }
  const char* backendName() const override { return pen_.backendName(); }
  void poll(int timeout_ms, std::vector<PenSample>& out) override {
    if (!released_) return;
    const size_t before = out.size();
    pen_.poll(timeout_ms, out);
    for (size_t i = before; i < out.size(); ++i)
      if (first_contact_ns_ == 0 && out[i].tipDown()) first_contact_ns_ = out[i].t_ns;
  }
  PenConnection connection() const override { return pen_.connection(); }
  const PenDeviceInfo& deviceInfo() const override { return pen_.deviceInfo(); }
  std::string statusMessage() const override { return pen_.statusMessage(); }

 private:
  ReplayPenSource& pen_;
  bool released_ = false;
  int64_t first_contact_ns_ = 0;
};

struct LatencyRun {
  FrameTimingStats stats;
  std::vector<double> lift_to_lit, lift_to_full;  // from the lift sample, with the journal sync
  bool ok = false;
};

// The loops compared, in the order run.
struct LoopVariant {
  const char* name;  // as printed
  const char* file;  // the session journal's name
  bool ink_first, late_ink;
};
constexpr LoopVariant kVariants[] = {
    {"baseline (the loop before late latching)", "baseline.cbj", false, false},
    {"ink first, latched once before the composite", "early.cbj", true, false},
    {"ink last (late ink: latched after the frame was made; the product)", "late.cbj", true, true},
};

LatencyRun runPainter(Display& display, VolumeRenderer& renderer, const Volume& cumulus,
                      const std::string& pen_journal, const std::string& session_journal, int w,
                      int h, const SkyExtent& sky, const LoopVariant& variant) {
  LatencyRun run;
  PaintSessionSettings settings{w, h, sky.grid};
  settings.sky_span = sky.span;
  settings.sky_max_span = sky.span;
  PaintSession session(settings, BrushConfig{}, MappingConfig{});
  session.setQuietMapping(true);
  std::string error;
  if (!session.replaceVolume(cumulus, 0, "bundled cumulus", &error)) {
    std::printf("  painter: %s\n", error.c_str());
    return run;
  }
  JournalWriter journal;  // the session's own journal: Frame records, stroke-end syncs
  if (!journal.open(session_journal)) {
    std::printf("  painter: %s\n", journal.error().c_str());
    return run;
  }
  session.recordTo(&journal, MonotonicClock().nowNs());
  ReplayOptions replay;
  replay.realtime = true;
  replay.restamp = true;
  ReplayPenSource replayed(pen_journal, replay);
  HeldPen pen(replayed);
  PaintLoopOptions options;
  options.max_seconds = 120.0;
  options.ink_first = variant.ink_first;
  options.late_ink = variant.late_ink;
  long presented = 0;
  options.each_iteration = [&](bool shown) {
    if (shown && ++presented == 2) pen.release();
  };
  const std::string dir = std::filesystem::path(pen_journal).parent_path().string();
  options.config_dir = dir + "/config";  // nothing there: built-in calibration
  options.state_dir = dir + "/state";
  PaintLoop loop(display, renderer, cumulus, Light{}, options);
  loop.attachPen(&pen, &session);
  PaintLoopSummary summary;
  if (!loop.run(nullptr, &summary, &error)) {
    std::printf("  painter: %s\n", error.c_str());
    return run;
  }
  session.recordTo(nullptr, 0);
  journal.close();
  std::vector<FrameRecord> frames;
  for (const JournalRecord& record : readJournal(session_journal).records)
    if (record.type == JournalRecordType::kFrame)
      if (auto f = decodeFrameRecord(record.t_ns, record.payload))
        if (f->present_ns >= pen.firstContactNs() &&
            (!f->hasSample() || f->oldest_sample_ns >= pen.firstContactNs()))
          frames.push_back(*f);  // from the first stroke on
  run.stats = frameTimingStats(frames);
  run.lift_to_lit = summary.lift_sample_to_lit_ms;
  run.lift_to_full = summary.lift_sample_to_refined_ms;
  run.ok = true;
  return run;
}

// `prefix` names a figure of a run between the baseline and the product ("early_").
void report(BenchReport* out, bool baseline, const LatencyRun& run,
            const std::string& prefix = "") {
  const auto put = [&](const std::string& key, double v) {
    baseline ? out->baseline(key, v) : out->figure(prefix + key, v);
  };
  const FrameTimingStats& s = run.stats;
  put("ready_p50_ms", s.sample_to_ready.p50);
  put("ready_p95_ms", s.sample_to_ready.p95);
  put("ready_p99_ms", s.sample_to_ready.p99);
  put("present_p50_ms", s.sample_to_present.p50);
  put("present_p95_ms", s.sample_to_present.p95);
  put("present_p99_ms", s.sample_to_present.p99);
  put("oldest_present_p95_ms", s.oldest_to_present.p95);
  put("interval_p95_ms", s.interval.p95);
  put("ink_frames", double(s.ink_frames));
  put("late_frames", double(s.missed_frames));
  put("lift_to_lit_ms", run.lift_to_lit.empty() ? -1 : median(run.lift_to_lit));
  put("lift_to_full_ms", run.lift_to_full.empty() ? -1 : median(run.lift_to_full));
}

}  // namespace

int benchLatency(int argc, char** argv) {
  Args args(argc, argv, {"help"});
  if (args.has("help")) {
    std::printf("%s", kHelp);
    return 0;
  }
  if (auto bad = args.unknown({"help", "size", "strokes", "gap-ms", "grid"}); !bad.empty()) {
    std::fprintf(stderr, "cloudbrush bench latency: unknown option %s (see --help)\n",
                 bad.front().c_str());
    return 2;
  }
  int w = 0, h = 0;
  const std::string size = args.get("size", "1920x1080");
  const int strokes = int(args.getInt("strokes", 6));
  const double gap_ms = args.getDouble("gap-ms", 250.0);
  const int grid = int(args.getInt("grid", 256));
  if (std::sscanf(size.c_str(), "%dx%d", &w, &h) != 2 || w < 16 || h < 16 || w > 8192 || h > 8192 ||
      strokes < 1 || gap_ms < 0 || grid < 16 || grid > 512 || !args.error().empty()) {
    std::fprintf(stderr,
                 "cloudbrush bench latency: bad option: --size WxH, --strokes >= 1, --gap-ms >= "
                 "0, --grid 16..512 %s\n",
                 args.error().c_str());
    return 2;
  }
  const SkyExtent sky{grid, kDefaultSkySpan};
  const Volume cumulus = placeInSky(makeBundledCumulus(glm::ivec3(grid), 1), sky);
  const std::string dir = std::filesystem::temp_directory_path().string() + "/cb_bench_latency_" +
                          std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  const std::string pen_journal = dir + "/pen.cbj";
  if (const std::string e = writePenJournal(pen_journal, w, h, strokes, gap_ms); !e.empty()) {
    std::fprintf(stderr, "cloudbrush bench latency: %s\n", e.c_str());
    return 1;
  }
  DisplayOptions display_options;
  display_options.platform = DisplayPlatform::Surfaceless;
  display_options.width = w;
  display_options.height = h;
  std::string error;
  std::unique_ptr<Display> display = openDisplay(display_options, &error);
  if (!display) {
    std::fprintf(stderr, "cloudbrush bench latency: no display (%s)\n", error.c_str());
    return 1;
  }
  std::printf(
      "bench latency: %dx%d surfaceless, %d strokes of a 200 Hz replayed pen %.0f ms apart, the "
      "bundled cumulus %d^3 in a %d x %d sky, %d worker threads (the machine may be shared: the "
      "baseline runs in the same process just before)\n",
      w, h, strokes, gap_ms, grid, sky.span, sky.span, workerThreads());
  BenchReport out("latency");
  LatencyRun runs[3];
  {
    VolumeRenderer renderer;
    if (!renderer.init(&error)) {
      std::fprintf(stderr, "cloudbrush bench latency: renderer: %s\n", error.c_str());
      return 1;
    }
    for (int i = 0; i < 3; ++i) {
      const LoopVariant& variant = kVariants[i];
      runs[i] = runPainter(*display, renderer, cumulus, pen_journal, dir + "/" + variant.file, w, h,
                           sky, variant);
      std::printf("%s:\n%s", variant.name, formatFrameTimingStats(runs[i].stats, "  ").c_str());
      std::printf(
          "  pen-up from the lift sample (with the stroke-end sync): lit %.1f ms, full "
          "resolution %.1f ms (medians)\n",
          runs[i].lift_to_lit.empty() ? -1.0 : median(runs[i].lift_to_lit),
          runs[i].lift_to_full.empty() ? -1.0 : median(runs[i].lift_to_full));
      std::fflush(stdout);
    }
  }
  const FrameTimingStats& s = runs[2].stats;
  std::printf("target sample -> frame ready p95 <= 8 ms: %s (%.1f); p99 <= 16.7 ms: %s (%.1f)\n",
              s.sample_to_ready.p95 <= 8.0 ? "met" : "MISSED", s.sample_to_ready.p95,
              s.sample_to_ready.p99 <= 16.7 ? "met" : "MISSED", s.sample_to_ready.p99);
  report(&out, false, runs[2]);
  report(&out, false, runs[1], "early_");
  report(&out, true, runs[0]);
  out.note("present", s.source);
  std::filesystem::remove_all(dir);
  out.print();
  return 0;
}

}  // namespace cb
