// `cloudbrush bench brush`: the cost of each pen sample for every brush at 200 Hz input
// on a 1280×720 footprint, against the naive 3D brush that ray-marches a fresh slice for every
// dab (the baseline, same run); and the painting-mode frame — cached scene + live footprint
// overlay + cursor — at 1280×720 on this machine's GL (llvmpipe here), against re-rendering the
// volume every frame. Targets: < 2 ms per sample for the 3D brush, ≥ 60 fps while painting.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "app/bench/bench_report.h"
#include "app/bench/benches.h"
#include "app/brush/brush_3d.h"
#include "app/brush/slice_sampler.h"
#include "app/brush/stroke_engine.h"
#include "app/brush/synthetic_strokes.h"
#include "app/cli/args.h"
#include "app/core/config_paths.h"
#include "app/render/footprint_overlay.h"
#include "app/render/gl/egl_context.h"
#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"
#include "app/volume/scene_generators.h"

namespace cb {
namespace {

using Clock = std::chrono::steady_clock;
// The workload: the eight strokes of 永 written large in the middle of the footprint, a pressure
// ramp, a tilt sweep and a fast gestural curve (dispersion on), all sampled at `rate_hz`.
std::vector<std::vector<BrushInput>> workload(int w, int h, double rate_hz) {
  std::vector<std::vector<BrushInput>> strokes;
  int64_t t = 0;
  auto add = [&](SyntheticStroke s) {
    strokes.push_back(sampleStroke(s, rate_hz, t));
    t = strokes.back().back().t_ns + 100000000;
  };
  const float offset = 0.5f * float(w - h);
  for (SyntheticStroke s : yongStrokes(h)) {
    for (glm::vec2& p : s.control_points) p.x += offset;
    add(s);
  }
  add(pressureRamp(w, h));
  add(tiltSweep(w, h));
  SyntheticStroke fast = gentleCurve(w, h);
  fast.speed_px_s = 2500.0f;
  add(fast);
  return strokes;
}

// A pen sample of the workload and whether the pen touches (the contact the calibration's
// hysteresis would report; the engine does not decide it).
struct ReportedSample {
  BrushInput input;
  bool contact = false;
};

// A stroke as the tablet reports it: the contact samples, a lifting sample 5 ms later, then the
// pen hovering for 50 ms (10 samples at 200 Hz, pressure 0) before the next stroke.
std::vector<ReportedSample> withLiftAndHover(const std::vector<BrushInput>& stroke) {
  std::vector<ReportedSample> out;
  for (const BrushInput& in : stroke) out.push_back({in, true});
  BrushInput hover = stroke.back();
  hover.pressure = 0.0f;
  for (int i = 1; i <= 11; ++i) {
    hover.t_ns += 5000000;
    out.push_back({hover, false});
  }
  return out;
}

// Drives the engine's explicit contact calls from a reported sample: tip-down, move, tip-up
// (the stroke is queued for takeFinishedStroke), hover.
FootprintRect feedReported(StrokeEngine& engine, const ReportedSample& s) {
  if (s.contact) return engine.inStroke() ? engine.addSample(s.input) : engine.beginStroke(s.input);
  if (engine.inStroke())
    engine.finishStroke();
  else
    engine.prepareNextStroke();
  return {};
}

struct SampleCosts {
  std::vector<double> ms;      // wall time, one per pen sample
  std::vector<double> cpu_ms;  // CPU time of all threads (immune to being descheduled)
  uint64_t dabs = 0;
};

// Feeds every stroke through a fresh engine, timing each sample (tip-down and tip-up included).
// The brush (and the 3D brush's ink volume) is built before timing starts.
SampleCosts timeBrush(const BrushConfig& base, BrushKind kind, bool cached_3d, int w, int h,
                      const std::vector<std::vector<BrushInput>>& strokes) {
  BrushConfig config = base;
  config.default_brush = kind;
  StrokeEngine engine(config, w, h);
  Brush& brush = engine.brush(kind);
  if (auto* b3 = dynamic_cast<Brush3D*>(&brush)) b3->setCaching(cached_3d);
  SampleCosts costs;
  for (const std::vector<BrushInput>& stroke : strokes) {
    for (const ReportedSample& in : withLiftAndHover(stroke)) {
      double c0 = processCpuMs();
      Clock::time_point t0 = Clock::now();
      feedReported(engine, in);
      costs.ms.push_back(msSince(t0));
      costs.cpu_ms.push_back(processCpuMs() - c0);
    }
    StrokeResult done;
    engine.takeFinishedStroke(&done);
  }
  if (auto* tb = dynamic_cast<TextureBrush*>(&brush)) costs.dabs = tb->dabCount();
  return costs;
}

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / double(v.size());
}

void printCosts(const char* name, const SampleCosts& c) {
  std::printf("  %-12s wall: median %.3f  mean %.3f  p95 %.3f  p99 %.3f  max %.3f ms\n", name,
              median(c.ms), mean(c.ms), percentile(c.ms, 95), percentile(c.ms, 99),
              percentile(c.ms, 100));
  std::printf("  %-12s cpu:  median %.3f  mean %.3f  p95 %.3f  p99 %.3f  max %.3f ms\n", "",
              median(c.cpu_ms), mean(c.cpu_ms), percentile(c.cpu_ms, 95), percentile(c.cpu_ms, 99),
              percentile(c.cpu_ms, 100));
}

// The timings of the painting-mode frame bench (milliseconds per frame or render).
struct OverlayFrameTimes {
  std::vector<double> scene_ms;     // the cached scene render
  std::vector<double> full_ms;      // the full composite after a camera move
  std::vector<double> frame_ms;     // brush + upload + overlay + finish
  std::vector<double> overlay_ms;   // the overlay draw alone
  std::vector<double> uncached_ms;  // baseline: ray cast + overlay every frame
  size_t texels = 0;                // uploaded in all
};

// Prints the painting-mode frame's figures and puts them in the report.
void reportOverlayFrames(const OverlayFrameTimes& t, int footprint_texels, int frames,
                         const std::string& renderer, BenchReport* report) {
  const double med = median(t.frame_ms), p95 = percentile(t.frame_ms, 95);
  std::printf("  scene render (cached once per camera move): median %.2f ms\n", median(t.scene_ms));
  std::printf(
      "  painting frame, brush + upload + overlay + finish: median %.2f ms (%.0f fps), "
      "p95 %.2f ms (%.0f fps); overlay draw alone median %.2f ms\n",
      med, 1000.0 / med, p95, 1000.0 / p95, median(t.overlay_ms));
  std::printf("  first frame after a camera move (full composite): median %.2f ms\n",
              median(t.full_ms));
  std::printf("  uploaded %.1f texels per frame on average (a full footprint is %d)\n",
              double(t.texels) / frames, footprint_texels);
  std::printf("  baseline, re-render volume + overlay every frame: median %.2f ms (%.0f fps)\n",
              median(t.uncached_ms), 1000.0 / median(t.uncached_ms));
  std::printf("  target >= 60 fps while painting: %s (p95 %s)\n",
              1000.0 / med >= 60.0 ? "met" : "MISSED", 1000.0 / p95 >= 60.0 ? "met" : "missed");
  report->figure("frame_painting_median_ms", med);
  report->figure("frame_painting_p95_ms", p95);
  report->figure("frame_painting_fps", 1000.0 / med);
  report->figure("frame_overlay_draw_median_ms", median(t.overlay_ms));
  report->figure("frame_scene_render_ms", median(t.scene_ms));
  report->figure("frame_full_composite_ms", median(t.full_ms));
  report->figure("frame_uploaded_texels_per_frame", double(t.texels) / frames);
  report->baseline("frame_uncached_median_ms", median(t.uncached_ms));
  report->baseline("frame_uncached_fps", 1000.0 / median(t.uncached_ms));
  report->note("frame_target", "painting frame >= 60 fps at 1280x720");
  report->note("gl_renderer", renderer);
}

// The painting-mode frame at w×h: returns false (with a note) when no GL context is available.
bool benchOverlayFrames(const BrushConfig& base, int w, int h, int frames, int volume_size,
                        BenchReport* report) {
  EglContext ctx;
  std::string error;
  if (!createSurfacelessContext(&ctx, &error)) {
    std::printf("frame: no GL context (%s); skipped\n", error.c_str());
    report->note("frame", "no GL context: " + error);
    return false;
  }
  std::printf("frame: %s, %s, %dx%d, cached scene = bundled cumulus %d³\n", ctx.renderer.c_str(),
              ctx.version.c_str(), w, h, volume_size);
  bool ok = true;
  {
    VolumeRenderer renderer;
    FootprintOverlay overlay;
    RenderTarget scene, frame;
    if (!renderer.init(&error) || !overlay.init(&error) ||
        !scene.create(w, h, RenderTarget::Format::kRgba8, &error) ||
        !frame.create(w, h, RenderTarget::Format::kRgba8, &error)) {
      std::printf("frame: GL setup failed: %s\n", error.c_str());
      report->note("frame", "GL setup failed: " + error);
      ok = false;
    } else {
      Volume volume = makeBundledCumulus(glm::ivec3(volume_size));
      Light light;
      renderer.sync(volume, light);
      Camera camera = Camera::reference();
      // The scene render that painting mode caches (also the per-frame cost without caching).
      std::vector<double> scene_ms;
      for (int i = 0; i < 3; ++i) {
        Clock::time_point t0 = Clock::now();
        renderer.render(camera, w, h, scene.fbo());
        glFinish();
        scene_ms.push_back(msSince(t0));
      }

      // Paint the 永 sequence at 200 Hz while drawing frames at 60 Hz of pen time: each frame
      // feeds the samples that arrived since the last one, uploads the changed rectangles and
      // draws cached scene + footprint + cursor.
      BrushConfig config = base;
      config.default_brush = BrushKind::k3D;
      StrokeEngine engine(config, w, h);
      std::vector<ReportedSample> samples;
      for (const auto& s : workload(w, h, 200.0)) {
        std::vector<ReportedSample> reported = withLiftAndHover(s);
        samples.insert(samples.end(), reported.begin(), reported.end());
      }
      // After a camera move the whole frame is composited once.
      overlay.beginFootprint(w, h);
      std::vector<double> full_ms;
      for (int i = 0; i < 3; ++i) {
        overlay.invalidate();
        Clock::time_point t0 = Clock::now();
        overlay.draw(scene.texture(), frame.fbo(), w, h, OverlayCursor{});
        glFinish();
        full_ms.push_back(msSince(t0));
      }
      std::vector<double> frame_ms, overlay_ms;
      size_t next = 0, texels = 0;
      bool was_in_stroke = false;
      const int64_t frame_ns = 16666667;
      OverlayCursor cursor;
      for (int f = 0; f < frames; ++f) {
        int64_t until = samples.front().input.t_ns + int64_t(f + 1) * frame_ns;
        Clock::time_point t0 = Clock::now();
        while (next < samples.size() && samples[next].input.t_ns <= until) {
          FootprintRect r = feedReported(engine, samples[next]);
          if (engine.inStroke() && !was_in_stroke) overlay.beginFootprint(w, h);
          was_in_stroke = engine.inStroke();
          if (engine.inStroke()) texels += overlay.upload(engine.footprint(), r);
          cursor.screen_px = samples[next].input.footprint_px;
          ++next;
          StrokeResult done;
          engine.takeFinishedStroke(&done);
        }
        if (next == samples.size()) next = 0;  // loop the workload for long runs
        Clock::time_point t1 = Clock::now();
        overlay.draw(scene.texture(), frame.fbo(), w, h, cursor);
        glFinish();
        overlay_ms.push_back(msSince(t1));
        frame_ms.push_back(msSince(t0));
      }
      // Baseline: the same frame without the cache (ray cast the volume, then the overlay).
      std::vector<double> uncached_ms;
      for (int f = 0; f < 5; ++f) {
        Clock::time_point t0 = Clock::now();
        renderer.render(camera, w, h, scene.fbo());
        overlay.draw(scene.texture(), frame.fbo(), w, h, cursor);
        glFinish();
        uncached_ms.push_back(msSince(t0));
      }
      reportOverlayFrames({scene_ms, full_ms, frame_ms, overlay_ms, uncached_ms, texels}, w * h,
                          frames, ctx.renderer, report);
    }
  }
  destroyGlContext(&ctx);
  return ok;
}

}  // namespace

int benchBrush(int argc, char** argv) {
  Args args(argc, argv, {"help", "no-gl"});
  if (args.has("help")) {
    std::printf(
        "usage: cloudbrush bench brush [--rate HZ] [--repeat N] [--frames N] [--volume N]\n"
        "                             [--config FILE] [--no-gl]\n"
        "  Cost per pen sample of the 2D, 3D and skeleton brushes on a 1280x720 footprint\n"
        "  (永 strokes, pressure ramp, tilt sweep, a fast curve) against the naive uncached 3D\n"
        "  brush; then the painting frame (cached scene + footprint overlay + cursor).\n"
        "  --rate HZ     pen report rate (default 200)\n"
        "  --repeat N    passes over the workload per brush (default 3)\n"
        "  --frames N    painting frames to time (default 300)\n"
        "  --volume N    cached scene volume size N³ (default 128)\n"
        "  --config FILE brush parameters (default: the shipped config/brush.toml)\n"
        "  --no-gl       skip the frame measurement\n");
    return 0;
  }
  std::vector<std::string> unknown =
      args.unknown({"help", "no-gl", "rate", "repeat", "frames", "volume", "config"});
  if (!unknown.empty()) {
    std::fprintf(stderr, "cloudbrush bench brush: unknown option %s (see --help)\n",
                 unknown[0].c_str());
    return 2;
  }
  double rate = args.getDouble("rate", 200.0);
  long repeat = args.getInt("repeat", 3), frames = args.getInt("frames", 300);
  long volume = args.getInt("volume", 128);
  if (!args.error().empty() || rate <= 0 || repeat < 1 || frames < 1 || volume < 8) {
    std::fprintf(stderr, "cloudbrush bench brush: %s\n",
                 args.error().empty() ? "rate, repeat, frames must be positive, volume >= 8"
                                      : args.error().c_str());
    return 2;
  }
  const int w = 1280, h = 720;
  BenchReport report("brush");
  std::vector<std::vector<BrushInput>> strokes = workload(w, h, rate);
  size_t n = 0;
  for (const auto& s : strokes) n += s.size();
  std::printf(
      "brush: %zu pen samples at %.0f Hz in %zu strokes on a %dx%d footprint (+11 lift/hover "
      "samples per stroke), %ld passes\n",
      n, rate, strokes.size(), w, h, repeat);

  BrushConfig config;
  std::vector<std::string> config_errors;
  std::string config_path = args.get("config", configFile("brush.toml"));
  if (!loadBrushConfig(config_path, &config, &config_errors))
    for (const std::string& e : config_errors)
      std::fprintf(stderr, "cloudbrush bench brush: %s (using the default)\n", e.c_str());
  std::printf("  brush parameters from %s\n", config_path.c_str());
  Clock::time_point t0 = Clock::now();
  auto ink =
      std::make_shared<const InkVolume>(config.brush3d.ink_volume_size, config.brush3d.ink_seed);
  double ink_ms = msSince(t0);
  t0 = Clock::now();
  const int slices = 50;
  for (int i = 0; i < slices; ++i)
    marchSlab(*ink, cuttingPlane(*ink, 0.02f * i, float(i - 25), 10.0f, 60.0f), config.brush3d);
  double slice_ms = msSince(t0) / slices;
  std::printf("  ink volume %d³ built once in %.1f ms; one slab ray-march (%d² sample) %.3f ms\n",
              ink->size(), ink_ms, config.brush3d.sample_size, slice_ms);

  struct Run {
    const char* name;
    BrushKind kind;
    bool cached;
  };
  const Run runs[] = {{"2d", BrushKind::k2D, true},
                      {"3d", BrushKind::k3D, true},
                      {"skeleton", BrushKind::kSkeleton, true},
                      {"3d_uncached", BrushKind::k3D, false}};
  for (const Run& run : runs) {
    SampleCosts all;
    for (long r = 0; r < repeat; ++r) {
      SampleCosts c = timeBrush(config, run.kind, run.cached, w, h, strokes);
      all.ms.insert(all.ms.end(), c.ms.begin(), c.ms.end());
      all.cpu_ms.insert(all.cpu_ms.end(), c.cpu_ms.begin(), c.cpu_ms.end());
      all.dabs += c.dabs;
    }
    printCosts(run.name, all);
    if (all.dabs)
      std::printf("  %-12s %.2f dabs per sample\n", "", double(all.dabs) / all.ms.size());
    std::string key = std::string("per_sample_") + run.name;
    auto put = [&](const std::string& k, double v) {
      run.cached ? report.figure(k, v) : report.baseline(k, v);
    };
    put(key + "_median_ms", median(all.ms));
    put(key + "_mean_ms", mean(all.ms));
    put(key + "_p95_ms", percentile(all.ms, 95));
    put(key + "_p99_ms", percentile(all.ms, 99));
    put(key + "_max_ms", percentile(all.ms, 100));
    put(key + "_cpu_mean_ms", mean(all.cpu_ms));
    put(key + "_cpu_p95_ms", percentile(all.cpu_ms, 95));
    put(key + "_cpu_p99_ms", percentile(all.cpu_ms, 99));
  }
  report.figure("ink_volume_build_ms", ink_ms);
  report.figure("slab_march_ms", slice_ms);
  report.note("per_sample_target", "3d brush < 2 ms per sample at 200 Hz");

  if (!args.has("no-gl")) benchOverlayFrames(config, w, h, int(frames), int(volume), &report);
  report.print();
  return 0;
}

}  // namespace cb
