// `cloudbrush bench mapping`: the stroke-to-cloud mapping (thesis ch. 6) on reference footprints
// — the single thick stroke of Fig. 6.6 and the heart of Fig. 6.9 at 1280×768, and the
// initial-diameter sweep of Table 6.1 — per stage (circle growth, sphere mapping, edge mapping,
// occupancy update, light update, texture upload) and in total: pen-up → volume and light
// ready, and pen-up → first lit frame (1280×720 through the VolumeRenderer on EGL surfaceless).
// Baseline in the same run: the straightforward variant the thesis started from (circle tests
// traverse every pixel, radius −4 px per attempt) with everything on one thread.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

#include "app/bench/bench_report.h"
#include "app/bench/benches.h"
#include "app/cli/args.h"
#include "app/core/config_paths.h"
#include "app/core/parallel_for.h"
#include "app/mapping/reference_strokes.h"
#include "app/mapping/stroke_mapper.h"
#include "app/render/gl/egl_context.h"
#include "app/render/light_volume.h"
#include "app/render/occupancy_pyramid.h"
#include "app/render/volume_renderer.h"

namespace cb {
namespace {

using Clock = std::chrono::steady_clock;

double threadCpuMs() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
}

constexpr int kFootprintW = 1280, kFootprintH = 768;
constexpr int kFrameW = 1280, kFrameH = 720;

// Medians over repetitions of one configuration.
struct StageFigures {
  double growth = 0, spheres = 0, edges = 0, mapping = 0, occupancy = 0, light = 0, upload = 0;
  double volume_light_ready = 0, first_lit_frame = -1;
  size_t circles = 0;
  int steps = 0;
  long long attempts = 0, edge_pixels = 0;
};

// The GPU side, when EGL surfaceless and GL 4.5 are available.
struct GpuSide {
  bool ok = false;
  EglContext context;
  VolumeRenderer renderer;
  RenderTarget target;
  std::string error;

  bool init() {
    if (!createSurfacelessContext(&context, &error)) return false;
    if (!renderer.init(&error)) return false;
    if (!target.create(kFrameW, kFrameH, RenderTarget::Format::kRgba8, &error)) return false;
    return ok = true;
  }
};

class MappingBench {
 public:
  MappingBench(int volume_size, int repeats, GpuSide* gpu)
      : volume_(glm::ivec3(volume_size)), repeats_(repeats), gpu_(gpu) {
    // What the app has at start: an empty sky with its occupancy and light volume.
    occupancy_ = buildOccupancy(volume_);
    sweepLightVolume(light_volume_, volume_, light_, volume_.bounds());
    if (gpu_->ok) gpu_->renderer.sync(volume_, light_);
  }

  // The product path: fast circle growth, all threads, GPU sync and the first frame.
  StageFigures runFast(const StrokeResult& stroke, const MappingConfig& config) {
    StrokeMapper mapper(config);
    mapper.setQuiet(true);
    std::vector<StageFigures> runs;
    for (int r = 0; r < repeats_; ++r) {
      reset();
      StageFigures f;
      const Clock::time_point pen_up = Clock::now();
      MappingReport rep = mapper.map(stroke, volume_);
      fillMapping(rep, &f);
      if (gpu_->ok) {
        SyncStats sync = gpu_->renderer.sync(volume_, light_);
        f.occupancy = sync.occupancy_ms;
        f.light = sync.light_ms;
        f.upload = sync.pack_ms + sync.upload_ms;
        f.volume_light_ready = rep.timings.total_ms + f.occupancy + f.light;
        RenderOptions options;
        options.finish = true;
        gpu_->renderer.render(stroke.view.camera, kFrameW, kFrameH, gpu_->target.fbo(), options);
        f.first_lit_frame = msSince(pen_up);
      } else {
        cpuOccupancyAndLight(rep.dirty, &f);
        f.volume_light_ready = msSince(pen_up);
      }
      runs.push_back(f);
    }
    return medianOf(runs);
  }

  // The baseline: straightforward circle growth, one thread for everything, CPU only.
  StageFigures runBaseline(const StrokeResult& stroke, const MappingConfig& config) {
    StrokeMapper mapper(config);
    mapper.setQuiet(true);
    mapper.setStraightforwardCircleGrowth(true);
    setWorkerThreads(1);
    std::vector<StageFigures> runs;
    for (int r = 0; r < repeats_; ++r) {
      reset();
      StageFigures f;
      const Clock::time_point pen_up = Clock::now();
      MappingReport rep = mapper.map(stroke, volume_);
      fillMapping(rep, &f);
      cpuOccupancyAndLight(rep.dirty, &f);
      f.volume_light_ready = msSince(pen_up);
      runs.push_back(f);
    }
    setWorkerThreads(0);
    return medianOf(runs);
  }

  // Circle growth alone (no volume work): for the diameter sweep. Growth runs on the calling
  // thread, so its thread CPU time is also reported (*cpu_ms): unlike wall time it does not
  // grow with other load on the machine.
  double growthOnly(const StrokeResult& s, const CircleGrowthConfig& c, bool straightforward,
                    CircleGrowthResult* out, double* cpu_ms) {
    std::vector<double> t, cpu;
    for (int r = 0; r < repeats_; ++r) {
      const double c0 = threadCpuMs();
      Clock::time_point t0 = Clock::now();
      *out = straightforward ? growCirclesStraightforward(s.footprint, s.path, c)
                             : growCircles(s.footprint, s.path, c);
      t.push_back(msSince(t0));
      cpu.push_back(threadCpuMs() - c0);
    }
    *cpu_ms = median(cpu);
    return median(t);
  }

 private:
  // Back to an empty sky, with occupancy, light and GPU copies in step (not timed).
  void reset() {
    volume_.fill(0.0f);
    updateOccupancy(occupancy_, volume_, volume_.bounds());
    sweepLightVolume(light_volume_, volume_, light_, volume_.bounds());
    if (gpu_->ok) gpu_->renderer.sync(volume_, light_);
  }

  void cpuOccupancyAndLight(const VoxelBox& dirty, StageFigures* f) {
    Clock::time_point t0 = Clock::now();
    updateOccupancy(occupancy_, volume_, dirty);
    f->occupancy = msSince(t0);
    t0 = Clock::now();
    sweepLightVolume(light_volume_, volume_, light_, dirty);
    f->light = msSince(t0);
  }

  static void fillMapping(const MappingReport& rep, StageFigures* f) {
    f->growth = rep.timings.circle_growth_ms;
    f->spheres = rep.timings.sphere_mapping_ms;
    f->edges = rep.timings.edge_mapping_ms;
    f->mapping = rep.timings.total_ms;
    f->circles = rep.circles.size();
    f->steps = rep.growth_steps;
    f->attempts = rep.circle_attempts;
    f->edge_pixels = rep.edges.leftover_pixels;
  }

  static StageFigures medianOf(const std::vector<StageFigures>& runs) {
    auto med = [&](double StageFigures::*field) {
      std::vector<double> v;
      for (const StageFigures& r : runs) v.push_back(r.*field);
      return median(v);
    };
    StageFigures m = runs.front();
    m.growth = med(&StageFigures::growth);
    m.spheres = med(&StageFigures::spheres);
    m.edges = med(&StageFigures::edges);
    m.mapping = med(&StageFigures::mapping);
    m.occupancy = med(&StageFigures::occupancy);
    m.light = med(&StageFigures::light);
    m.upload = med(&StageFigures::upload);
    m.volume_light_ready = med(&StageFigures::volume_light_ready);
    m.first_lit_frame = med(&StageFigures::first_lit_frame);
    return m;
  }

  Volume volume_;
  Light light_;
  OccupancyPyramid occupancy_;
  LightVolume light_volume_;
  int repeats_;
  GpuSide* gpu_;
};

void printStages(const char* name, const StageFigures& f) {
  std::printf(
      "  %-22s circles %4zu steps %3d attempts %6lld edge px %6lld | growth %8.2f  spheres %7.2f  "
      "edges %7.2f (mapping %7.2f)  occupancy %6.2f  light %7.2f  upload %6.2f | ready %8.2f ms",
      name, f.circles, f.steps, f.attempts, f.edge_pixels, f.growth, f.spheres, f.edges, f.mapping,
      f.occupancy, f.light, f.upload, f.volume_light_ready);
  if (f.first_lit_frame >= 0) std::printf("  first lit frame %8.2f ms", f.first_lit_frame);
  std::printf("\n");
}

void addStages(BenchReport* report, const std::string& prefix, const StageFigures& f,
               bool baseline) {
  auto put = [&](const std::string& key, double v) {
    if (baseline)
      report->baseline(prefix + key, v);
    else
      report->figure(prefix + key, v);
  };
  put("circles", double(f.circles));
  put("attempts", double(f.attempts));
  put("circle_growth_ms", f.growth);
  put("sphere_mapping_ms", f.spheres);
  put("edge_mapping_ms", f.edges);
  put("mapping_ms", f.mapping);
  put("occupancy_ms", f.occupancy);
  put("light_ms", f.light);
  if (!baseline) put("texture_upload_ms", f.upload);
  put("volume_and_light_ready_ms", f.volume_light_ready);
  if (f.first_lit_frame >= 0) put("first_lit_frame_ms", f.first_lit_frame);
}

const char* verdict(bool met) {
  return met ? "met" : "MISSED";
}

// The load average at the start (timings are wall clock), printed and noted.
void noteLoadAverage(BenchReport* report) {
  if (FILE* f = std::fopen("/proc/loadavg", "r")) {
    char line[128] = {0};
    if (std::fgets(line, sizeof line, f)) {
      std::string load(line);
      while (!load.empty() && load.back() == '\n') load.pop_back();
      std::printf("load average at start: %s (timings are wall clock; other load inflates them)\n",
                  load.c_str());
      report->note("loadavg", load);
    }
    std::fclose(f);
  }
}

// Table 6.1's initial-diameter sweep on the single stroke, circle growth only, against the
// one-thread baseline; the d32 full pipeline's pen-up -> volume and light ready, returned.
double sweepInitialDiameter(MappingBench& bench, const StrokeResult& thick,
                            const MappingConfig& config, BenchReport* report) {
  std::printf("initial-diameter sweep on the single stroke (Table 6.1), circle growth only:\n");
  std::printf("  %8s %8s %6s %9s %10s %12s %8s | %9s %13s %8s\n", "diameter", "circles", "steps",
              "attempts", "growth ms", "baseline ms", "ratio", "cpu ms", "baseline cpu", "ratio");
  double d32_total = 0.0;
  for (int diameter : {256, 196, 128, 96, 64, 32}) {
    CircleGrowthConfig c = config.circles;
    c.initial_diameter_px = diameter;
    CircleGrowthResult fast, slow;
    double cpu_fast = 0, cpu_slow = 0;
    double t_fast = bench.growthOnly(thick, c, false, &fast, &cpu_fast);
    setWorkerThreads(1);
    double t_slow = bench.growthOnly(thick, c, true, &slow, &cpu_slow);
    setWorkerThreads(0);
    std::printf("  %8d %8zu %6d %9lld %10.2f %12.2f %7.1fx | %9.2f %13.2f %7.1fx\n", diameter,
                fast.circles.size(), fast.steps, fast.attempts, t_fast, t_slow,
                t_slow / std::max(1e-9, t_fast), cpu_fast, cpu_slow,
                cpu_slow / std::max(1e-9, cpu_fast));
    const std::string k = "sweep_d" + std::to_string(diameter) + "_";
    report->figure(k + "circles", double(fast.circles.size()));
    report->figure(k + "steps", fast.steps);
    report->figure(k + "attempts", double(fast.attempts));
    report->figure(k + "circle_growth_ms", t_fast);
    report->figure(k + "circle_growth_cpu_ms", cpu_fast);
    report->baseline(k + "circle_growth_cpu_ms", cpu_slow);
    report->baseline(k + "circles", double(slow.circles.size()));
    report->baseline(k + "attempts", double(slow.attempts));
    report->baseline(k + "circle_growth_ms", t_slow);
    if (diameter == 32) {
      MappingConfig c32 = config;
      c32.circles.initial_diameter_px = 32;
      StageFigures f = bench.runFast(thick, c32);
      d32_total = f.volume_light_ready;
      printStages("  d32 full pipeline", f);
      report->figure("sweep_d32_volume_and_light_ready_ms", d32_total);
    }
  }
  return d32_total;
}

// The reference strokes' figures, each against its baseline.
struct ReferenceStages {
  StageFigures thick_fast, thick_base, heart_fast, heart_base, heart_many;
};

// The speed-ups and the targets, met or MISSED.
void reportMappingTargets(const ReferenceStages& r, double d32_total, BenchReport* report) {
  const StageFigures &thick_fast = r.thick_fast, &thick_base = r.thick_base;
  const StageFigures &heart_fast = r.heart_fast, &heart_base = r.heart_base;
  const StageFigures& heart_many = r.heart_many;
  const double speedup = thick_base.volume_light_ready / thick_fast.volume_light_ready;
  const double heart_speedup = heart_base.volume_light_ready / heart_fast.volume_light_ready;
  const double growth_speedup = thick_base.growth / std::max(1e-9, thick_fast.growth);
  const double mapping_speedup = thick_base.mapping / std::max(1e-9, thick_fast.mapping);
  const double heart_mapping_speedup = heart_base.mapping / std::max(1e-9, heart_fast.mapping);
  report->figure("single_speedup_vs_baseline", speedup);
  report->figure("heart_speedup_vs_baseline", heart_speedup);
  report->figure("single_circle_growth_speedup_vs_baseline", growth_speedup);
  report->figure("single_mapping_speedup_vs_baseline", mapping_speedup);
  report->figure("heart_mapping_speedup_vs_baseline", heart_mapping_speedup);

  std::printf("targets:\n");
  std::printf("  single stroke pen-up -> volume and light ready %.1f ms <= 100 ms: %s\n",
              thick_fast.volume_light_ready, verdict(thick_fast.volume_light_ready <= 100.0));
  std::printf(
      "  heart pen-up -> volume and light ready %.1f ms (%zu circles), %.1f ms (%zu "
      "circles) <= 250 ms: %s\n",
      heart_fast.volume_light_ready, heart_fast.circles, heart_many.volume_light_ready,
      heart_many.circles,
      verdict(std::max(heart_fast.volume_light_ready, heart_many.volume_light_ready) <= 250.0));
  if (thick_fast.first_lit_frame >= 0)
    std::printf("  single stroke pen-up -> first lit frame %.1f ms <= 200 ms: %s\n",
                thick_fast.first_lit_frame, verdict(thick_fast.first_lit_frame <= 200.0));
  else
    std::printf("  pen-up -> first lit frame: not measured (no renderer)\n");
  std::printf(
      "  speed-up vs baseline, pen-up -> volume and light ready: %.1fx (single), %.1fx "
      "(heart) >= 8x: %s\n",
      speedup, heart_speedup, verdict(speedup >= 8.0 && heart_speedup >= 8.0));
  std::printf(
      "  speed-up vs baseline, mapping alone: %.1fx (single), %.1fx (heart); circle "
      "growth alone %.1fx (single)\n",
      mapping_speedup, heart_mapping_speedup, growth_speedup);
  std::printf("  diameter 32 pen-up -> volume and light ready %.1f ms < 1000 ms: %s\n", d32_total,
              verdict(d32_total < 1000.0));
  report->note("targets",
               "ready<=100ms single, <=250ms heart, first lit frame<=200ms, >=8x baseline, "
               "d32<1s");
}

}  // namespace

int benchMapping(int argc, char** argv) {
  Args args(argc, argv, {"help", "no-gl"});
  if (args.has("help")) {
    std::printf(
        "usage: cloudbrush bench mapping [--repeat N] [--volume N] [--no-gl]\n\n"
        "Times the hybrid mapping (thesis ch. 6) on reference footprints (1280x768): the thick\n"
        "stroke of Fig. 6.6, the heart of Fig. 6.9 and the initial-diameter sweep of Table 6.1,\n"
        "per stage and pen-up to first lit frame (1280x720, EGL surfaceless), against the\n"
        "straightforward one-thread variant measured in the same run.\n"
        "  --repeat N   repetitions per figure, median reported (default 5)\n"
        "  --volume N   volume resolution N^3 (default 256)\n"
        "  --no-gl      skip the renderer (no texture upload / first-frame figures)\n");
    return 0;
  }
  if (auto bad = args.unknown({"help", "no-gl", "repeat", "volume"}); !bad.empty()) {
    std::fprintf(stderr, "cloudbrush bench mapping: unknown option %s (see --help)\n",
                 bad.front().c_str());
    return 2;
  }
  const int repeats = int(args.getInt("repeat", 5));
  const int volume_size = int(args.getInt("volume", 256));
  if (!args.error().empty() || repeats < 1 || volume_size < 16 || volume_size > 512) {
    std::fprintf(stderr,
                 "cloudbrush bench mapping: bad option (%s); --repeat >= 1, --volume 16..512\n",
                 args.error().empty() ? "out of range" : args.error().c_str());
    return 2;
  }

  GpuSide gpu;
  if (!args.has("no-gl") && !gpu.init())
    std::printf("renderer unavailable (%s): no upload / first-frame figures\n", gpu.error.c_str());
  MappingConfig config;
  try {
    config = loadMappingConfig(configFile("mapping.toml"));
  } catch (const std::exception& e) {
    std::printf("using built-in mapping defaults (%s)\n", e.what());
  }
  std::printf("mapping bench: footprint %dx%d, volume %d^3, %d threads, %d repeats (medians)%s\n",
              kFootprintW, kFootprintH, volume_size, workerThreads(), repeats,
              gpu.ok ? (", renderer: " + gpu.context.renderer).c_str() : "");

  BenchReport report("mapping");
  noteLoadAverage(&report);
  MappingBench bench(volume_size, repeats, &gpu);
  const StrokeResult thick = makeThickStroke(kFootprintW, kFootprintH, 1);
  const StrokeResult heart = makeHeart(kFootprintW, kFootprintH, 2);

  std::printf("reference strokes (initial diameter %d):\n", config.circles.initial_diameter_px);
  const StageFigures thick_fast = bench.runFast(thick, config);
  printStages("single stroke", thick_fast);
  const StageFigures thick_base = bench.runBaseline(thick, config);
  printStages("  baseline", thick_base);
  const StageFigures heart_fast = bench.runFast(heart, config);
  printStages("heart", heart_fast);
  const StageFigures heart_base = bench.runBaseline(heart, config);
  printStages("  baseline", heart_base);
  // The thesis's heart has 163 circles; with the thesis's Empty Test on the initial circle this
  // heart grows fewer, bigger circles. Testing the smallest circle instead gives a load of
  // about that many circles.
  MappingConfig many = config;
  many.circles.empty_test_on_smallest = true;
  const StageFigures heart_many = bench.runFast(heart, many);
  printStages("heart, many circles", heart_many);
  const StageFigures heart_many_base = bench.runBaseline(heart, many);
  printStages("  baseline", heart_many_base);
  addStages(&report, "heart_many_", heart_many, false);
  addStages(&report, "heart_many_", heart_many_base, true);
  addStages(&report, "single_", thick_fast, false);
  addStages(&report, "single_", thick_base, true);
  addStages(&report, "heart_", heart_fast, false);
  addStages(&report, "heart_", heart_base, true);

  const double d32_total = sweepInitialDiameter(bench, thick, config, &report);
  reportMappingTargets({thick_fast, thick_base, heart_fast, heart_base, heart_many}, d32_total,
                       &report);
  report.print();
  return 0;
}

}  // namespace cb
