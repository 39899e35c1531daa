// `cloudbrush bench scale`: how the painter's figures scale with the screen and the thread count,
// so an installer can size a machine. For each of 1280×720, 1920×1080 and 3840×2160
// and for 1 and 2 threads — each thread count in a child process of this binary with
// CLOUDBRUSH_THREADS and LP_NUM_THREADS set, because llvmpipe reads LP_NUM_THREADS when its
// context is created — on EGL surfaceless:
//   - a fresh full-resolution lit frame of the bundled cumulus (256³, reference camera), cast as
//     the painter casts a frame at rest (at the volume's detail, volume_detail.h), and with a
//     ray per pixel as the baseline;
//   - the orbit of the painter itself (PaintLoop without a pen, the bundled cumulus): frames per
//     second at the moving scale its policy settles on (nextMovingScale, never below 0.5);
//   - the painter with a replayed pen (PaintLoop, the session opened on the bundled cumulus, the
//     reference strokes): painting-frame time, pen-up → first lit frame (reduced scale) and →
//     full-resolution lit frame, with the region re-render (changed_region.h) and, as the
//     baseline in the same run, with whole-frame re-renders (PaintLoopOptions::region_rerender).
// Pen-up is timed from the lift sample's own timestamp to glFinish of the frame: the replayed pen
// plays on its real time line at 200 Hz and stamps each sample with the time it played, as a
// tablet's kernel timestamp is (ReplayOptions::restamp), and the session journals to a file, so
// the figure holds the wait for the loop, the mapping and the journal's stroke-end fsync (until
// now it ran from the painter receiving the lift, without a journal: printed as "received").
// Every run paints in the product's default sky (sky_extent.h: 4 × 4 home boxes, 1024×256×1024
// for grid 256). The sky-size table then repeats the painter at 1920×1080 in skies of 1, 4 and
// 16 home boxes' area (spans 1, 2, 4; span 1 is the thesis's one 256³ box, the baseline), with
// the memory each holds: the volume's bricks, the renderer's GPU copies and light volume, and the
// process's RSS. Never fails on a missed target.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "app/bench/bench_report.h"
#include "app/bench/bench_reprojection.h"
#include "app/bench/bench_scale_actions.h"
#include "app/bench/benches.h"
#include "app/cli/args.h"
#include "app/core/parallel_for.h"
#include "app/render/gl/display.h"
#include "app/render/render_target.h"
#include "app/render/temporal_reprojection.h"
#include "app/render/volume_renderer.h"
#include "app/scene/paint_camera.h"
#include "app/session/paint_session.h"
#include "app/session/synthetic_session.h"
#include "app/shell/painter/paint_loop.h"
#include "app/volume/scene_generators.h"
#include "app/volume/sky_extent.h"
#include "drivers/replay/replay_pen_source.h"

namespace cb {
namespace {

const char kHelp[] =
    "usage: cloudbrush bench scale [--sizes WxH,...] [--threads N,...] [--frames N] [--grid N]\n"
    "  --sizes LIST    screen sizes (default 1280x720,1920x1080,3840x2160)\n"
    "  --threads LIST  thread counts, each in a child process (default 1,2)\n"
    "  --frames N      timed fresh frames per size, median (default 5; 2 at 3840x2160)\n"
    "  --grid N        home box N^3 (default 256, the painter's)\n"
    "  --sky-spans L   sky spans of the sky-size table at 1920x1080 (default 1,2,4: 1x, 4x, 16x\n"
    "                  the home box's area; 0 skips the table)\n"
    "  --parts LIST    all (default), or some of orbit,pen,actions (the fresh frames always run)\n"
    "  (--child runs one thread count in this process; the parent starts it)\n"
    "Targets at 1920x1080 with 2 threads: fresh frame <= 100 ms, the orbit as the painter\n"
    "draws it >= 30 fps (its moving frames at the volume's detail or reprojected, whichever\n"
    "is the faster; the half-resolution orbit is the baseline), painting >= 60 fps, pen-up ->\n"
    "first lit <= 100 ms, -> full resolution <= 150 ms.\n";

using Clock = std::chrono::steady_clock;

struct Size {
  int w = 0, h = 0;
  std::string name() const { return std::to_string(w) + "x" + std::to_string(h); }
  bool huge() const { return double(w) * h > 4e6; }
};

bool parseSizes(const std::string& text, std::vector<Size>* sizes) {
  size_t start = 0;
  while (start <= text.size()) {
    const size_t end = std::min(text.find(',', start), text.size());
    Size s;
    if (std::sscanf(text.substr(start, end - start).c_str(), "%dx%d", &s.w, &s.h) != 2 ||
        s.w < 16 || s.h < 16 || s.w > 8192 || s.h > 8192)
      return false;
    sizes->push_back(s);
    start = end + 1;
  }
  return !sizes->empty();
}

// Figures of one size in one child process.
struct Row {
  double volume_mb = -1, gpu_mb = -1, light_mb = -1, rss_mb = -1;  // after the painter's strokes
  double fresh_ms = -1, fresh_first_ms = -1, fresh_cpu_ms = -1, fresh_paint_view_ms = -1;
  double fresh_every_pixel_ms = -1;  // the baseline: a ray per pixel
  double fresh_start_view_ms = -1;   // what the painter first shows: its empty sky there
  double orbit_fps = -1, orbit_scale = -1, orbit_cpu_ms = -1;  // reprojected (full resolution)
  double orbit_base_fps = -1, orbit_base_scale = -1, orbit_base_cpu_ms = -1;  // half resolution
  // The painter's default (MovingFrames::kFaster) and the share of its frames reprojected.
  double orbit_default_fps = -1, orbit_default_cpu_ms = -1, orbit_default_reprojected = -1;
  ReprojectedOrbitFigures reprojected;  // beside the half-resolution orbit, in one process
  double painting_ms = -1;
  double lit_ms = -1, full_ms = -1, lit_pixels = -1, full_pixels = -1;  // region path
  double lit_base_ms = -1, full_base_ms = -1;                           // whole-frame baseline
  double lit_received_ms = -1;  // pen-up -> lit from the painter receiving the lift
  double mapping_ms = -1, sync_ms = -1, lit_render_ms = -1, full_render_ms = -1;
  PainterActionFigures actions, actions_base;  // at 1920x1080 only (bench_scale_actions.h)
};

// The painter with the replayed reference strokes over the bundled cumulus.
struct PaintRun {
  double painting_ms = -1, lit_ms = -1, full_ms = -1, mapping_ms = -1;
  double lit_pixels = -1, full_pixels = -1;
  double lit_render_ms = -1, full_render_ms = -1, sync_ms = -1;  // parts: ray cast, sync
  // Memory after the strokes: the session's volume bricks, the renderer's GPU copies and its
  // light volume (bytes counted by each), and the process's resident set.
  double volume_mb = -1, gpu_mb = -1, light_mb = -1, rss_mb = -1;
  // The first stroke alone (the one that grows the sky in the growth case), and the sky after.
  double first_lit_ms = -1, first_full_ms = -1, first_sync_ms = -1;
  int sky_span = 0;
  double lit_received_ms = -1;  // from the painter receiving the lift (the earlier figure)
};

std::string writeStrokeJournal(const std::string& dir, Size size, int strokes) {
  const std::string path = dir + "/strokes.cbj";
  PaintSession recorder({size.w, size.h, 32}, BrushConfig{}, MappingConfig{});
  recorder.setQuietMapping(true);
  JournalWriter journal;
  if (!journal.open(path)) return "";
  recorder.recordTo(&journal, 0);
  const PenDeviceInfo tablet = syntheticTablet(size.w, size.h);
  recorder.setDevice(tablet, 0);
  int64_t t0 = 1'000'000'000;
  const std::vector<SyntheticStroke> reference = referencePaintStrokes(size.w, size.h);
  for (int i = 0; i < strokes; ++i) {
    const std::vector<PenSample> samples = syntheticPenSamples(
        reference[size_t(i) % reference.size()], tablet, size.w, size.h, 200.0, t0);
    for (const PenSample& s : samples) recorder.feed(s);
    t0 = samples.back().t_ns + 500'000'000;
  }
  return path;
}

double medianOr(const std::vector<double>& v) {
  return v.empty() ? -1.0 : median(v);
}

// `view`: the paint view the strokes are drawn from (null: the session's starting view);
// `max_span`: how wide the sky may grow (0: a sky of `sky`'s span throughout, as the sky-size
// table's rows need).
PaintRun runPainter(Display& display, VolumeRenderer& renderer, const Volume& cumulus,
                    const std::string& journal, Size size, const SkyExtent& sky, bool region,
                    const Camera* view = nullptr, int max_span = 0) {
  PaintRun run;
  PaintSessionSettings settings{size.w, size.h, sky.grid};
  settings.sky_span = sky.span;
  settings.sky_max_span = max_span > 0 ? max_span : sky.span;
  PaintSession session(settings, BrushConfig{}, MappingConfig{});
  session.setQuietMapping(true);
  std::string error;
  if (!session.replaceVolume(cumulus, 0, "bundled cumulus", &error)) {
    std::printf("  painter: %s\n", error.c_str());
    return run;
  }
  if (view && !session.apply(ui::SetCamera{*view}, 0, &error)) {
    std::printf("  painter: %s\n", error.c_str());
    return run;
  }
  const std::string dir = std::filesystem::path(journal).parent_path().string();
  JournalWriter session_journal;  // journalled as the product does: the stroke-end fsync counts
  if (!session_journal.open(dir + "/session.cbj")) {
    std::printf("  painter: %s\n", session_journal.error().c_str());
    return run;
  }
  session.recordTo(&session_journal, 0);
  ReplayOptions replay;
  replay.realtime = true;
  replay.restamp = true;
  ReplayPenSource pen(journal, replay);
  PaintLoopOptions options;
  options.max_seconds = 300.0;  // a bound for a stuck loop; the replay's end ends it
  options.region_rerender = region;
  options.cast_at_volume_detail = region;  // the baseline casts a ray per pixel, as before
  options.config_dir = dir + "/config";    // nothing there: built-in calibration
  options.state_dir = dir + "/state";
  std::vector<double> lit_pixels, full_pixels, lit_render, full_render, sync;
  options.on_frame = [&](const PaintFrameInfo& info) {
    if (info.first_lit_after_lift) {
      lit_pixels.push_back(double(info.rendered_pixels));
      lit_render.push_back(info.render_ms);
      sync.push_back(info.sync_ms);
    }
    if (info.refined_after_lift) {
      full_pixels.push_back(double(info.rendered_pixels));
      full_render.push_back(info.render_ms);
    }
  };
  const Light light;
  PaintLoop loop(display, renderer, cumulus, light, options);
  loop.attachPen(&pen, &session);
  PaintLoopSummary summary;
  if (!loop.run(nullptr, &summary, &error)) {
    std::printf("  painter: %s\n", error.c_str());
    return run;
  }
  session.recordTo(nullptr, 0);
  run.painting_ms = summary.median_painting_frame_ms;
  run.lit_ms = medianOr(summary.lift_sample_to_lit_ms);
  run.full_ms = medianOr(summary.lift_sample_to_refined_ms);
  run.lit_received_ms = medianOr(summary.pen_up_to_lit_ms);
  run.mapping_ms = medianOr(summary.mapping_ms);
  run.lit_pixels = medianOr(lit_pixels);
  run.full_pixels = medianOr(full_pixels);
  run.lit_render_ms = medianOr(lit_render);
  run.full_render_ms = medianOr(full_render);
  run.sync_ms = medianOr(sync);
  if (!summary.lift_sample_to_lit_ms.empty())
    run.first_lit_ms = summary.lift_sample_to_lit_ms.front();
  if (!summary.lift_sample_to_refined_ms.empty())
    run.first_full_ms = summary.lift_sample_to_refined_ms.front();
  if (!sync.empty()) run.first_sync_ms = sync.front();
  run.sky_span = session.sky().span;
  run.volume_mb = mb(session.volume().memoryBytes());
  run.gpu_mb = mb(renderer.memoryBytes());
  run.light_mb = mb(renderer.lightVolume().memoryBytes());
  run.rss_mb = processRssMb();
  return run;
}

// Fresh full-resolution frames: every pixel ray cast (no cached image), after the first frame
// that pays llvmpipe's shader compile; at the reference camera, at the painter's starting view
// and of its empty sky there. False when the target cannot be made.
bool measureFreshFrames(VolumeRenderer& renderer, const Volume& cumulus, Size size, int frames,
                        int grid, Row* row) {
  RenderTarget target;
  std::string error;
  if (!target.create(size.w, size.h, RenderTarget::Format::kRgba8, &error)) {
    std::printf("  %s: %s\n", size.name().c_str(), error.c_str());
    return false;
  }
  renderer.sync(cumulus, Light{});
  RenderOptions still;
  still.finish = true;
  still.cast_at_volume_detail = true;  // as the painter casts a frame at rest
  renderer.render(Camera::reference(), size.w, size.h, target.fbo(), still);
  row->fresh_first_ms = renderer.lastStats().frame_ms;
  std::vector<double> fresh, cpu;
  const int n = size.huge() ? std::min(frames, 2) : frames;
  for (int i = 0; i < n; ++i) {
    const double c0 = processCpuMs();
    renderer.render(Camera::reference().orbited(float(i)), size.w, size.h, target.fbo(), still);
    cpu.push_back(processCpuMs() - c0);
    fresh.push_back(renderer.lastStats().frame_ms);
  }
  row->fresh_ms = median(fresh);
  row->fresh_cpu_ms = median(cpu);
  fresh.clear();
  RenderOptions every_pixel = still;
  every_pixel.cast_at_volume_detail = false;
  renderer.render(Camera::reference(), size.w, size.h, target.fbo(), every_pixel);  // its program
  for (int i = 0; i < n; ++i) {
    renderer.render(Camera::reference().orbited(float(i)), size.w, size.h, target.fbo(),
                    every_pixel);
    fresh.push_back(renderer.lastStats().frame_ms);
  }
  row->fresh_every_pixel_ms = median(fresh);
  // The same at the painter's starting view (framed on the drawable region: the cumulus fills
  // more of the screen), which the pen-up figures are drawn from.
  const Camera paint_view = initialPaintCamera(PaintSessionSettings{size.w, size.h, grid});
  auto atPaintView = [&] {
    fresh.clear();
    for (int i = 0; i < std::max(1, n / 2); ++i) {
      renderer.render(paint_view, size.w, size.h, target.fbo(), still);
      fresh.push_back(renderer.lastStats().frame_ms);
    }
    return median(fresh);
  };
  row->fresh_paint_view_ms = atPaintView();
  // The painter's first screen: its session's empty sky (the product's default span) at that
  // view, as `cloudbrush paint` starts (app/shell/painter/paint_screen.h).
  const PaintSession empty(PaintSessionSettings{size.w, size.h, grid}, BrushConfig{},
                           MappingConfig{});
  renderer.sync(empty.volume(), Light{});
  row->fresh_start_view_ms = atPaintView();
  renderer.sync(cumulus, Light{});
  std::printf(
      "  %s: fresh frame %.1f ms (process CPU %.1f ms; first frame %.1f ms; a ray per pixel "
      "%.1f ms); at the painter's starting view %.1f ms (its empty sky there, the first screen: "
      "%.1f ms)\n",
      size.name().c_str(), row->fresh_ms, row->fresh_cpu_ms, row->fresh_first_ms,
      row->fresh_every_pixel_ms, row->fresh_paint_view_ms, row->fresh_start_view_ms);
  std::fflush(stdout);
  return true;
}

// The painter's orbit: its own loop and moving-frame policy, no pen. Full resolution by
// temporal reprojection; the baseline, in the same run: the half-resolution orbit
// (MovingFrames::kReduced, the moving-scale policy); and the painter's default, whichever of
// the two keeps to the frame budget or is the faster (MovingFrames::kFaster). Then the
// reprojected orbit against the half-resolution one in alternating blocks, from the painter's
// starting view (frames as PNG into $CLOUDBRUSH_BENCH_SHOTS when set).
void measureOrbits(Display& display, VolumeRenderer& renderer, const Volume& cumulus, Size size,
                   int grid, Row* row) {
  std::string error;
  for (MovingFrames way :
       {MovingFrames::kReduced, MovingFrames::kReprojected, MovingFrames::kFaster}) {
    PaintLoopOptions options;
    options.max_frames = size.huge() ? 24 : 48;
    options.moving_frames = way;
    // The baseline as the painter had it: every moving frame at the moving scale.
    options.cast_at_volume_detail = way != MovingFrames::kReduced;
    PaintLoop loop(display, renderer, cumulus, Light{}, options);
    PaintLoopSummary summary;
    const double cpu0 = processCpuMs();
    double fps = -1, cpu = -1;
    if (loop.run(nullptr, &summary, &error)) {
      fps = summary.median_frame_ms > 0 ? 1000.0 / summary.median_frame_ms : -1;
      // Mean process CPU per frame (all threads): the figure to compare on a loaded machine.
      if (summary.frames > 0) cpu = (processCpuMs() - cpu0) / double(summary.frames);
    }
    if (way == MovingFrames::kFaster) {
      const long moving = summary.reprojected_moving_frames + summary.reduced_moving_frames;
      row->orbit_default_fps = fps;
      row->orbit_default_cpu_ms = cpu;
      row->orbit_default_reprojected =
          moving > 0 ? double(summary.reprojected_moving_frames) / double(moving) : -1;
      std::printf(
          "  %s: painter's orbit as it chooses (the faster way) %.1f fps, %.0f%% of its frames "
          "reprojected (process CPU %.1f ms a frame)\n",
          size.name().c_str(), fps, 100.0 * row->orbit_default_reprojected, cpu);
      std::fflush(stdout);
      continue;
    }
    const bool reproject = way == MovingFrames::kReprojected;
    const float scale = reproject ? 1.0f : orbitRenderScale(summary.final_moving_scale, options);
    (reproject ? row->orbit_fps : row->orbit_base_fps) = fps;
    (reproject ? row->orbit_cpu_ms : row->orbit_base_cpu_ms) = cpu;
    (reproject ? row->orbit_scale : row->orbit_base_scale) = scale;
    std::printf("  %s: painter's orbit %s %.1f fps at scale %.2f (process CPU %.1f ms a frame)\n",
                size.name().c_str(), reproject ? "reprojected" : "(baseline, reduced)", fps, scale,
                cpu);
    std::fflush(stdout);
  }
  const Camera paint_view = initialPaintCamera(PaintSessionSettings{size.w, size.h, grid});
  const char* shots = std::getenv("CLOUDBRUSH_BENCH_SHOTS");
  row->reprojected = measureReprojectedOrbit(renderer, paint_view, size.w, size.h,
                                             reprojectionFactor(size.w, size.h),
                                             size.huge() ? 2 : 4, shots ? shots : "");
  const ReprojectedOrbitFigures& r = row->reprojected;
  std::printf(
      "  %s: reprojected orbit (1 pixel in %d cast) %.1f ms a frame (%.1f fps; CPU %.1f ms), "
      "error mean %.2f/255, p99 %.0f/255; half-resolution orbit (baseline) %.1f ms (%.1f "
      "fps; CPU %.1f ms), error mean %.2f/255, p99 %.0f/255\n",
      size.name().c_str(), r.factor * r.factor, r.ms, 1000.0 / r.ms, r.cpu_ms, r.error_mean,
      r.error_p99, r.base_ms, 1000.0 / r.base_ms, r.base_cpu_ms, r.base_error_mean,
      r.base_error_p99);
  std::printf(
      "  %s: reprojected frame's parts: cast %.1f ms, reprojection pass %.1f ms, copy %.1f ms\n",
      size.name().c_str(), r.cast_ms, r.reproject_ms, r.copy_ms);
  std::printf(
      "  %s: orbit cast at the volume's detail (scale %.2f, as the painter's moving frames) %.1f "
      "ms a frame (%.1f fps; CPU %.1f ms), error mean %.2f/255, p99 %.0f/255\n",
      size.name().c_str(), r.detail_scale, r.detail_ms, 1000.0 / r.detail_ms, r.detail_cpu_ms,
      r.detail_error_mean, r.detail_error_p99);
  std::fflush(stdout);
}

// The painter with a pen: the region re-render, then the whole-frame baseline (not when quick).
void measurePen(Display& display, VolumeRenderer& renderer, const Volume& cumulus,
                const std::string& journal, Size size, const SkyExtent& sky, bool quick, Row* row) {
  const PaintRun region = runPainter(display, renderer, cumulus, journal, size, sky, true);
  const PaintRun whole =
      quick ? PaintRun{} : runPainter(display, renderer, cumulus, journal, size, sky, false);
  row->volume_mb = region.volume_mb;
  row->gpu_mb = region.gpu_mb;
  row->light_mb = region.light_mb;
  row->rss_mb = region.rss_mb;
  row->painting_ms = region.painting_ms;
  row->lit_ms = region.lit_ms;
  row->full_ms = region.full_ms;
  row->lit_pixels = region.lit_pixels;
  row->full_pixels = region.full_pixels;
  row->mapping_ms = region.mapping_ms;
  row->sync_ms = region.sync_ms;
  row->lit_render_ms = region.lit_render_ms;
  row->full_render_ms = region.full_render_ms;
  row->lit_received_ms = region.lit_received_ms;
  row->lit_base_ms = whole.lit_ms;
  row->full_base_ms = whole.full_ms;
  std::printf(
      "  %s: painting %.1f ms/frame; pen-up -> lit %.1f ms (mapping %.1f, sync %.1f, ray "
      "cast %.1f), -> full %.1f ms (ray cast %.1f) with the region (%.0f / %.0f pixels "
      "cast); whole frame: %.1f, %.1f ms; all from the lift sample's timestamp with the "
      "journal's stroke-end fsync (-> lit from the painter receiving the lift: %.1f ms)\n",
      size.name().c_str(), row->painting_ms, row->lit_ms, row->mapping_ms, row->sync_ms,
      row->lit_render_ms, row->full_ms, row->full_render_ms, row->lit_pixels, row->full_pixels,
      row->lit_base_ms, row->full_base_ms, row->lit_received_ms);
  std::printf(
      "  %s: memory after the strokes: volume %.1f MiB, GPU copies %.1f MiB, light %.1f MiB "
      "(process RSS %.0f MiB)\n",
      size.name().c_str(), row->volume_mb, row->gpu_mb, row->light_mb, row->rss_mb);
  std::fflush(stdout);
}

// The sky growing (sky_extent.h): the strokes drawn from the default view panned to the default
// sky's +x edge, so the first grows the sky; at its pen-up the renderer follows the growth
// (shifts what it holds, VolumeRenderer::sync) and the painter re-renders the stroke's region.
// Baseline in the same run: the same strokes in a sky made that wide from the start.
void measureGrowth(Display& display, VolumeRenderer& renderer, const std::string& journal,
                   Size size, const SkyExtent& sky, const std::string& k, BenchReport& report) {
  const int grid = sky.grid;
  const Volume home = makeBundledCumulus(glm::ivec3(grid), 1);
  const glm::vec3 edge(float(sky.span), 0.0f, 0.0f);
  const Camera view = defaultPaintCamera(Canvas{}, glm::vec3(-1.0f) + edge, glm::vec3(1.0f) + edge,
                                         float(size.w) / size.h);
  const PaintRun grows =
      runPainter(display, renderer, home, journal, size, sky, true, &view, kMaxSkySpan);
  const PaintRun wide =
      grows.sky_span > sky.span
          ? runPainter(display, renderer, home, journal, size, {grid, grows.sky_span}, true, &view)
          : PaintRun{};
  std::printf(
      "  %s: the stroke that grows the sky (span %d -> %d): pen-up -> lit %.1f ms (sync "
      "%.1f), -> full %.1f ms; in a sky that wide from the start (baseline): %.1f ms "
      "(sync %.1f), %.1f ms\n",
      size.name().c_str(), sky.span, grows.sky_span, grows.first_lit_ms, grows.first_sync_ms,
      grows.first_full_ms, wide.first_lit_ms, wide.first_sync_ms, wide.first_full_ms);
  std::fflush(stdout);
  report.figure(k + "growth_sky_span", double(grows.sky_span));
  report.figure(k + "growth_pen_up_to_lit_ms", grows.first_lit_ms);
  report.figure(k + "growth_pen_up_to_full_ms", grows.first_full_ms);
  report.figure(k + "growth_sync_ms", grows.first_sync_ms);
  report.baseline(k + "growth_pen_up_to_lit_ms", wide.first_lit_ms);
  report.baseline(k + "growth_pen_up_to_full_ms", wide.first_full_ms);
  report.baseline(k + "growth_sync_ms", wide.first_sync_ms);
}

// What a person does at the painter (bench_scale_actions.h): the painter's choices, then its
// earlier ones as the baseline, in this process.
void measureActions(Display& display, VolumeRenderer& renderer, const Volume& cumulus, Size size,
                    const SkyExtent& sky, const std::string& dir, Row* row) {
  for (bool baseline : {false, true}) {
    PainterActionFigures& a = baseline ? row->actions_base : row->actions;
    a = measurePainterActions(display, renderer, cumulus, size.w, size.h, sky, dir, baseline);
    std::printf(
        "  %s: the painter%s: light drag %.1f fps (%d frames; CPU %.1f ms a frame), release -> "
        "lit %.1f ms (CPU %.1f ms), -> full light at full resolution %.1f ms; picture placed -> "
        "lit %.1f ms, model %.1f ms; wind %.1f fps (%d frames; CPU %.1f ms a frame); camera "
        "drag %.1f fps (CPU %.1f ms a frame); mouse move -> on screen: light drag %.1f ms, camera "
        "drag %.1f ms; moving frames: %ld reprojected, %ld at the moving scale\n",
        size.name().c_str(),
        baseline
            ? " as before (baseline: the light volume swept in full every drag frame at the moving "
              "scale, whole-frame "
              "re-render, moving frames at the moving scale)"
            : "",
        a.light_drag_fps, a.drag_frames, a.light_drag_cpu_ms, a.light_release_ms,
        a.light_release_cpu_ms, a.light_release_full_ms, a.place_picture_ms, a.place_model_ms,
        a.wind_fps, a.wind_frames, a.wind_cpu_ms, a.camera_drag_fps, a.camera_drag_cpu_ms,
        a.light_drag_seen_ms, a.camera_drag_seen_ms, a.moving_reprojected, a.moving_reduced);
    std::fflush(stdout);
  }
}

void reportActions(BenchReport& report, const std::string& k, const Row& row) {
  for (bool baseline : {false, true}) {
    const PainterActionFigures& a = baseline ? row.actions_base : row.actions;
    if (a.drag_frames == 0 && a.place_picture_ms < 0) continue;
    const auto put = [&](const std::string& key, double v) {
      baseline ? report.baseline(k + key, v) : report.figure(k + key, v);
    };
    put("light_drag_fps", a.light_drag_fps);
    put("light_release_lit_ms", a.light_release_ms);
    put("light_release_full_ms", a.light_release_full_ms);
    put("place_picture_lit_ms", a.place_picture_ms);
    put("place_model_lit_ms", a.place_model_ms);
    put("wind_fps", a.wind_fps);
    put("light_drag_cpu_ms", a.light_drag_cpu_ms);
    put("light_release_cpu_ms", a.light_release_cpu_ms);
    put("wind_cpu_ms", a.wind_cpu_ms);
    put("camera_drag_fps", a.camera_drag_fps);
    put("camera_drag_cpu_ms", a.camera_drag_cpu_ms);
    put("light_drag_seen_ms", a.light_drag_seen_ms);
    put("camera_drag_seen_ms", a.camera_drag_seen_ms);
  }
}

// One size's row into the report, each key prefixed with `k` ("1920x1080_").
void reportRow(BenchReport& report, const std::string& k, const Row& row) {
  reportActions(report, k, row);
  report.figure(k + "fresh_ms", row.fresh_ms);
  report.baseline(k + "fresh_ms", row.fresh_every_pixel_ms);
  report.figure(k + "fresh_first_ms", row.fresh_first_ms);
  report.figure(k + "fresh_cpu_ms", row.fresh_cpu_ms);
  report.figure(k + "fresh_paint_view_ms", row.fresh_paint_view_ms);
  report.figure(k + "fresh_start_view_ms", row.fresh_start_view_ms);
  report.figure(k + "orbit_fps", row.orbit_fps);
  report.figure(k + "orbit_scale", row.orbit_scale);
  report.figure(k + "orbit_cpu_ms", row.orbit_cpu_ms);
  report.baseline(k + "orbit_fps", row.orbit_base_fps);
  report.baseline(k + "orbit_scale", row.orbit_base_scale);
  report.baseline(k + "orbit_cpu_ms", row.orbit_base_cpu_ms);
  report.figure(k + "orbit_default_fps", row.orbit_default_fps);
  report.figure(k + "orbit_default_cpu_ms", row.orbit_default_cpu_ms);
  report.figure(k + "orbit_default_reprojected_share", row.orbit_default_reprojected);
  const ReprojectedOrbitFigures& rep = row.reprojected;
  report.figure(k + "reprojected_orbit_fps", rep.ms > 0 ? 1000.0 / rep.ms : -1);
  report.figure(k + "reprojected_orbit_cpu_ms", rep.cpu_ms);
  report.figure(k + "reprojected_orbit_factor", rep.factor);
  report.figure(k + "reprojected_error_mean", rep.error_mean);
  report.figure(k + "reprojected_error_p99", rep.error_p99);
  report.figure(k + "reprojected_cast_ms", rep.cast_ms);
  report.figure(k + "reprojected_pass_ms", rep.reproject_ms);
  report.figure(k + "reprojected_copy_ms", rep.copy_ms);
  report.figure(k + "detail_orbit_fps", rep.detail_ms > 0 ? 1000.0 / rep.detail_ms : -1);
  report.figure(k + "detail_orbit_scale", rep.detail_scale);
  report.figure(k + "detail_orbit_cpu_ms", rep.detail_cpu_ms);
  report.figure(k + "detail_error_mean", rep.detail_error_mean);
  report.figure(k + "detail_error_p99", rep.detail_error_p99);
  report.baseline(k + "reprojected_orbit_fps", rep.base_ms > 0 ? 1000.0 / rep.base_ms : -1);
  report.baseline(k + "reprojected_orbit_cpu_ms", rep.base_cpu_ms);
  report.baseline(k + "reprojected_error_mean", rep.base_error_mean);
  report.baseline(k + "reprojected_error_p99", rep.base_error_p99);
  report.figure(k + "painting_ms", row.painting_ms);
  report.figure(k + "pen_up_to_lit_ms", row.lit_ms);
  report.figure(k + "pen_up_to_full_ms", row.full_ms);
  report.figure(k + "pen_up_received_to_lit_ms", row.lit_received_ms);
  report.figure(k + "lit_pixels_cast", row.lit_pixels);
  report.figure(k + "full_pixels_cast", row.full_pixels);
  report.figure(k + "mapping_ms", row.mapping_ms);
  report.figure(k + "sync_ms", row.sync_ms);
  report.figure(k + "lit_ray_cast_ms", row.lit_render_ms);
  report.figure(k + "full_ray_cast_ms", row.full_render_ms);
  report.figure(k + "volume_mb", row.volume_mb);
  report.figure(k + "gpu_mb", row.gpu_mb);
  report.figure(k + "light_mb", row.light_mb);
  report.figure(k + "rss_mb", row.rss_mb);
  report.baseline(k + "pen_up_to_lit_ms", row.lit_base_ms);
  report.baseline(k + "pen_up_to_full_ms", row.full_base_ms);
}

// One thread count (this process's): every size, in a sky of `sky`. `quick`: the fresh frames
// and the painter with the region re-render only (the sky-size table).
// `parts`: "all", or a comma-separated list of orbit, pen, actions (the fresh frames always run).
int runChild(const std::vector<Size>& sizes, int frames, const SkyExtent& sky, bool quick,
             const std::string& parts) {
  const auto want = [&](const std::string& part) {
    return parts == "all" || ("," + parts + ",").find("," + part + ",") != std::string::npos;
  };
  BenchReport report("scale");
  const int grid = sky.grid;
  const auto t_gen = Clock::now();
  const Volume cumulus = placeInSky(makeBundledCumulus(glm::ivec3(grid), 1), sky);
  const glm::ivec3 sd = sky.dims();
  std::printf(
      "  bundled cumulus %d^3 in a %dx%dx%d sky, generated in %.0f ms, %d worker threads, "
      "LP_NUM_THREADS=%s\n",
      grid, sd.x, sd.y, sd.z, msSince(t_gen), workerThreads(),
      std::getenv("LP_NUM_THREADS") ? std::getenv("LP_NUM_THREADS") : "(unset)");
  const std::string dir = std::filesystem::temp_directory_path().string() + "/cb_bench_scale_" +
                          std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  for (const Size& size : sizes) {
    Row row;
    const std::string k = size.name() + "_";
    DisplayOptions display_options;
    display_options.platform = DisplayPlatform::Surfaceless;
    display_options.width = size.w;
    display_options.height = size.h;
    std::string error;
    std::unique_ptr<Display> display = openDisplay(display_options, &error);
    if (!display) {
      std::printf("  %s: no display (%s)\n", size.name().c_str(), error.c_str());
      continue;
    }
    std::printf("  %s: rendered by %s%s%s\n", size.name().c_str(),
                display->context().describe().c_str(),
                display->context().device_note.empty() ? "" : "; passed over: ",
                display->context().device_note.c_str());
    {
      VolumeRenderer renderer;
      if (!renderer.init(&error)) {
        std::printf("  %s: renderer: %s\n", size.name().c_str(), error.c_str());
        continue;
      }
      if (!measureFreshFrames(renderer, cumulus, size, frames, grid, &row)) continue;
      if (!quick && want("orbit")) measureOrbits(*display, renderer, cumulus, size, grid, &row);
      const int strokes = size.huge() ? 1 : 2;
      const std::string journal = writeStrokeJournal(dir, size, strokes);
      if (!journal.empty() && want("pen"))
        measurePen(*display, renderer, cumulus, journal, size, sky, quick, &row);
      // Once, at 1920x1080 in the default sky.
      if (!quick && size.w == 1920 && size.h == 1080 && sky.span == kDefaultSkySpan) {
        if (!journal.empty() && want("pen"))
          measureGrowth(*display, renderer, journal, size, sky, k, report);
        if (want("actions")) measureActions(*display, renderer, cumulus, size, sky, dir, &row);
      }
    }
    display.reset();
    reportRow(report, k, row);
  }
  std::filesystem::remove_all(dir);
  report.print();
  return 0;
}

// The figures of a child's JSON line ("key":number pairs; "figures" before "baseline").
void parseReport(const std::string& json, std::map<std::string, double>* figures,
                 std::map<std::string, double>* baseline) {
  const size_t split = json.find("\"baseline\"");
  const std::regex pair("\"([A-Za-z0-9_]+)\":(-?[0-9.eE+-]+)");
  for (auto it = std::sregex_iterator(json.begin(), json.end(), pair); it != std::sregex_iterator();
       ++it) {
    const bool is_baseline = split != std::string::npos && size_t(it->position()) > split;
    (is_baseline ? *baseline : *figures)[(*it)[1]] = std::stod((*it)[2]);
  }
}

std::string cell(double v, const char* format) {
  if (v < 0) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

const char* verdict(bool met) {
  return met ? "met" : "MISSED";
}
// A target's verdict for a figure that is < 0 when its part of the bench did not run.
const char* verdict(double figure, bool met) {
  return figure < 0 ? "not measured" : verdict(met);
}

// A comma-separated list of integers in lo..hi; false when it is not one.
bool parseIntList(const std::string& list, int lo, int hi, std::vector<int>* out) {
  size_t start = 0;
  while (start <= list.size()) {
    const size_t end = std::min(list.find(',', start), list.size());
    const int v = std::atoi(list.substr(start, end - start).c_str());
    if (v < lo || v > hi) return false;
    out->push_back(v);
    start = end + 1;
  }
  return true;
}

using Figures = std::map<std::string, double>;

// Starts this binary as `bench scale --child` with a thread count and reads its figures.
struct ChildRunner {
  std::string self;  // this binary
  int frames = 5, grid = 256;
  std::string parts = "all";

  // One child process: `t` threads, the figures of its JSON line into *figures / *baselines
  // (its other output passed through).
  void run(int t, const std::string& sizes_arg, int span, bool quick, Figures* figures_out,
           Figures* baselines_out) const {
    const std::string command =
        "CLOUDBRUSH_THREADS=" + std::to_string(t) + " LP_NUM_THREADS=" + std::to_string(t) + " '" +
        self + "' bench scale --child --sizes " + sizes_arg + " --frames " +
        std::to_string(frames) + " --grid " + std::to_string(grid) + " --sky-span " +
        std::to_string(span) + (quick ? " --quick" : "") + " --parts " + parts;
    FILE* p = popen((command + " 2>/dev/null").c_str(), "r");
    if (!p) {
      std::printf("  could not start the child process\n");
      return;
    }
    // Whole lines, however long (the JSON line runs to several kilobytes).
    std::string last, line;
    char buf[4096];
    while (std::fgets(buf, sizeof buf, p)) {
      line += buf;
      if (line.back() != '\n' && !std::feof(p)) continue;
      if (line.rfind("{\"bench\"", 0) == 0)
        last = line;
      else
        std::fputs(line.c_str(), stdout), std::fflush(stdout);
      line.clear();
    }
    const int status = pclose(p);
    if (last.empty()) {
      std::printf("  the child process gave no figures (status %d)\n", status);
      return;
    }
    parseReport(last, figures_out, baselines_out);
  }
};

void noteLoadAverage(BenchReport& report) {
  FILE* f = std::fopen("/proc/loadavg", "r");
  if (!f) return;
  char line[128] = {0};
  if (std::fgets(line, sizeof line, f)) {
    std::string load(line);
    while (!load.empty() && load.back() == '\n') load.pop_back();
    std::printf("load average at start: %s (wall-clock figures; other load inflates them)\n",
                load.c_str());
    report.note("loadavg", load);
  }
  std::fclose(f);
}

// The children's figures by thread count.
struct ThreadFigures {
  std::map<int, Figures> figures, baselines;
  double get(int t, const Size& s, const std::string& key, bool baseline = false) const {
    const auto& by_thread = baseline ? baselines : figures;
    const auto m = by_thread.find(t);
    if (m == by_thread.end()) return -1.0;
    auto it = m->second.find(s.name() + "_" + key);
    return it == m->second.end() ? -1.0 : it->second;
  }
};

// The table of sizes and thread counts, into the report as t<threads>_<size>_<key>.
void printSizeTable(BenchReport& report, const std::vector<Size>& sizes,
                    const std::vector<int>& threads, const ThreadFigures& f) {
  std::printf("\n%-10s %3s | %9s | %8s %5s | %9s | %-21s | %-21s\n", "size", "thr", "fresh ms",
              "orbit fps", "scale", "paint ms", "pen-up->lit ms (base)", "->full res ms (base)");
  for (const Size& s : sizes)
    for (int t : threads) {
      const std::string lit = cell(f.get(t, s, "pen_up_to_lit_ms"), "%.1f") + " (" +
                              cell(f.get(t, s, "pen_up_to_lit_ms", true), "%.1f") + ")";
      const std::string full = cell(f.get(t, s, "pen_up_to_full_ms"), "%.1f") + " (" +
                               cell(f.get(t, s, "pen_up_to_full_ms", true), "%.1f") + ")";
      std::printf("%-10s %3d | %9s | %8s %5s | %9s | %-21s | %-21s\n", s.name().c_str(), t,
                  cell(f.get(t, s, "fresh_ms"), "%.1f").c_str(),
                  cell(f.get(t, s, "orbit_fps"), "%.1f").c_str(),
                  cell(f.get(t, s, "orbit_scale"), "%.2f").c_str(),
                  cell(f.get(t, s, "painting_ms"), "%.1f").c_str(), lit.c_str(), full.c_str());
      const std::string k = "t" + std::to_string(t) + "_" + s.name() + "_";
      for (const char* key :
           {"fresh_ms", "orbit_fps", "orbit_scale", "painting_ms", "pen_up_to_lit_ms",
            "pen_up_to_full_ms", "lit_pixels_cast", "full_pixels_cast", "mapping_ms", "volume_mb",
            "gpu_mb", "light_mb", "rss_mb"})
        report.figure(k + key, f.get(t, s, key));
      for (const char* key : {"pen_up_to_lit_ms", "pen_up_to_full_ms"})
        report.baseline(k + key, f.get(t, s, key, true));
    }
}

// The targets, at 1920x1080 with 2 threads.
void printTargets(const ThreadFigures& f) {
  const Size hd{1920, 1080};
  const double fresh = f.get(2, hd, "fresh_ms"), fps = f.get(2, hd, "orbit_fps"),
               scale = f.get(2, hd, "orbit_scale"), paint = f.get(2, hd, "painting_ms"),
               lit = f.get(2, hd, "pen_up_to_lit_ms"), full = f.get(2, hd, "pen_up_to_full_ms");
  std::printf("\ntargets at 1920x1080, 2 threads:\n");
  std::printf("  fresh full-resolution lit frame %.1f ms <= 100 ms: %s\n", fresh,
              verdict(fresh, fresh <= 100));
  std::printf("  orbit (half resolution, baseline) %.1f fps (process CPU %.1f ms a frame)\n",
              f.get(2, hd, "orbit_fps", true), f.get(2, hd, "orbit_cpu_ms", true));
  // The orbit as the painter draws it: its moving frames cast at the volume's detail, or
  // reprojected where that is the faster (the reprojected orbit alone is a reference).
  const double painter = f.get(2, hd, "orbit_default_fps");
  std::printf(
      "  orbit as the painter draws it %.1f fps >= 30: %s (every frame reprojected: %.1f "
      "fps at scale %.2f)\n",
      painter, verdict(painter, painter >= 30), fps, scale);
  std::printf("  painting %.1f ms/frame (%.0f fps) >= 60 fps: %s\n", paint,
              paint > 0 ? 1000 / paint : 0.0, verdict(paint, paint > 0 && paint <= 1000.0 / 60.0));
  std::printf("  pen-up -> first lit frame %.1f ms <= 100 ms: %s\n", lit, verdict(lit, lit <= 100));
  std::printf("  pen-up -> full-resolution lit frame %.1f ms <= 150 ms: %s\n", full,
              verdict(full, full <= 150));
}

// One row of what a person does: the figure, its baseline from the same child, the target.
struct PersonRow {
  const char* act;   // what the person does
  const char* key;   // the figure's key at its size
  Size size;         // the size the figure is measured at
  const char* base;  // what the baseline is
  const char* base_key;
  Size base_size;
  bool base_is_baseline;  // the baseline's key is in the child's "baseline" (else "figures")
  double target;
  bool at_least;  // the target is a floor (fps), else a ceiling (ms)
  const char* unit;
};

// Every row of the table of what a person does, measured in the children at 1920x1080 (and
// 3840x2160 for the large screen), with its baseline from the same process; into the report as
// t<threads>_person_<key>.
void printPersonTable(BenchReport& report, const std::vector<int>& threads,
                      const ThreadFigures& f) {
  const Size hd{1920, 1080}, uhd{3840, 2160};
  const PersonRow rows[] = {
      {"open the painter: its starting view, fresh frame", "fresh_start_view_ms", hd,
       "the cumulus at that view", "fresh_paint_view_ms", hd, false, 100, false, "ms"},
      {"pen-up -> full resolution", "pen_up_to_full_ms", hd, "whole-frame re-render",
       "pen_up_to_full_ms", hd, true, 150, false, "ms"},
      {"drag the light", "light_drag_fps", hd, "full sweep every frame", "light_drag_fps", hd, true,
       15, true, "fps"},
      // A move waits at most a frame to be read and a frame to be drawn: two frames at the
      // drag's frame-rate target.
      {"light drag: mouse move -> on screen", "light_drag_seen_ms", hd, "full sweep every frame",
       "light_drag_seen_ms", hd, true, 2000.0 / 15, false, "ms"},
      {"light change (release) -> lit frame", "light_release_lit_ms", hd, "full sweep every frame",
       "light_release_lit_ms", hd, true, 100, false, "ms"},
      {"orbit as the painter draws it (the faster way)", "orbit_default_fps", hd, "half resolution",
       "orbit_fps", hd, true, 30, true, "fps"},
      {"3840x2160 orbit as the painter draws it", "orbit_default_fps", uhd, "half resolution",
       "orbit_fps", uhd, true, 15, true, "fps"},
      // The painter's other way for moving frames, which it takes where it is the faster (on
      // llvmpipe mostly the cast at the volume's detail is, with less error): a reference, the
      // orbit's targets are the rows above.
      {"orbit, every frame reprojected (reference)", "orbit_fps", hd, "half resolution",
       "orbit_fps", hd, true, 0, true, "fps"},
      {"drag the view round (Camera mode)", "camera_drag_fps", hd, "at the moving scale",
       "camera_drag_fps", hd, true, 30, true, "fps"},
      {"view drag: mouse move -> on screen", "camera_drag_seen_ms", hd, "at the moving scale",
       "camera_drag_seen_ms", hd, true, 2000.0 / 30, false, "ms"},
      {"place a picture -> lit frame", "place_picture_lit_ms", hd, "whole-frame re-render",
       "place_picture_lit_ms", hd, true, 300, false, "ms"},
      {"place a model -> lit frame", "place_model_lit_ms", hd, "whole-frame re-render",
       "place_model_lit_ms", hd, true, 300, false, "ms"},
      {"wind on the 256^3 cumulus", "wind_fps", hd, "at the moving scale", "wind_fps", hd, true, 15,
       true, "fps"},
      {"3840x2160 fresh frame", "fresh_ms", uhd, "a ray per pixel", "fresh_ms", uhd, true, 200,
       false, "ms"},
  };
  for (int t : threads) {
    std::printf("\nwhat a person does, %d thread%s:\n%-48s | %9s | %-22s %9s | %-9s\n", t,
                t == 1 ? "" : "s", "act", "measured", "baseline (same run)", "", "target");
    for (const PersonRow& r : rows) {
      const double v = f.get(t, r.size, r.key);
      const double b = f.get(t, r.base_size, r.base_key, r.base_is_baseline);
      const bool met = v >= 0 && (r.at_least ? v >= r.target : v <= r.target);
      char target[32] = "-";  // a target of 0: a figure for reference
      if (r.target > 0)
        std::snprintf(target, sizeof target, "%s %.0f %s", r.at_least ? ">=" : "<=", r.target,
                      r.unit);
      std::printf("%-48s | %6s %-3s | %-22s %6s %-3s | %-9s %s\n", r.act, cell(v, "%.1f").c_str(),
                  r.unit, r.base, cell(b, "%.1f").c_str(), r.unit, target,
                  v < 0           ? "not measured"
                  : r.target <= 0 ? ""
                                  : verdict(met));
      const std::string k = "t" + std::to_string(t) + "_person_" + r.size.name() + "_" + r.key;
      report.figure(k, v);
      report.baseline(k, b);
    }
  }
}

// The sky-size table: the painter at 1920x1080 in skies of 1x, 4x, 16x the home box's area;
// span 1 (the thesis's one box) is the baseline.
void benchSkySizes(BenchReport& report, const ChildRunner& runner, const std::vector<int>& threads,
                   const std::vector<int>& spans) {
  const Size hd{1920, 1080};
  std::printf(
      "\nsky sizes at %s (the painter with the region re-render; span 1 = one %d^3 box, "
      "the baseline):\n",
      hd.name().c_str(), runner.grid);
  std::map<std::pair<int, int>, Figures> sky_figures;
  for (int t : threads)
    for (int span : spans) {
      std::printf("threads %d, sky span %d:\n", t, span);
      std::fflush(stdout);
      Figures unused;
      runner.run(t, hd.name(), span, true, &sky_figures[{t, span}], &unused);
    }
  std::printf("\n%-16s %3s | %8s | %14s | %14s | %9s %9s %9s %9s\n", "sky (voxels)", "thr",
              "fresh ms", "pen-up->lit ms", "->full res ms", "volume MB", "GPU MB", "light MB",
              "RSS MB");
  for (int t : threads)
    for (int span : spans) {
      const Figures& m = sky_figures[{t, span}];
      const auto at = [&](const std::string& key) {
        auto it = m.find(hd.name() + "_" + key);
        return it == m.end() ? -1.0 : it->second;
      };
      const glm::ivec3 d = SkyExtent{runner.grid, span}.dims();
      const std::string name =
          std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
      std::printf("%-16s %3d | %8s | %14s | %14s | %9s %9s %9s %9s\n", name.c_str(), t,
                  cell(at("fresh_ms"), "%.1f").c_str(),
                  cell(at("pen_up_to_lit_ms"), "%.1f").c_str(),
                  cell(at("pen_up_to_full_ms"), "%.1f").c_str(),
                  cell(at("volume_mb"), "%.1f").c_str(), cell(at("gpu_mb"), "%.1f").c_str(),
                  cell(at("light_mb"), "%.1f").c_str(), cell(at("rss_mb"), "%.0f").c_str());
      const std::string k = "t" + std::to_string(t) + "_sky" + std::to_string(span) + "_";
      for (const char* key : {"fresh_ms", "pen_up_to_lit_ms", "pen_up_to_full_ms", "volume_mb",
                              "gpu_mb", "light_mb", "rss_mb"})
        (span == 1 ? report.baseline(k + key, at(key)) : report.figure(k + key, at(key)));
    }
}

}  // namespace

int benchScale(int argc, char** argv) {
  Args args(argc, argv, {"help", "child", "quick"});
  if (args.has("help")) {
    std::printf("%s", kHelp);
    return 0;
  }
  if (auto bad = args.unknown({"help", "child", "quick", "sizes", "threads", "frames", "grid",
                               "sky-span", "sky-spans", "parts"});
      !bad.empty()) {
    std::fprintf(stderr, "cloudbrush bench scale: unknown option %s (see --help)\n",
                 bad.front().c_str());
    return 2;
  }
  std::vector<Size> sizes;
  const std::string size_list = args.get("sizes", "1280x720,1920x1080,3840x2160");
  const int frames = int(args.getInt("frames", 5));
  const int grid = int(args.getInt("grid", 256));
  if (!parseSizes(size_list, &sizes) || !args.error().empty() || frames < 1 || grid < 16 ||
      grid > 512) {
    std::fprintf(stderr,
                 "cloudbrush bench scale: bad option (%s): --sizes WxH,... (16..8192), --frames "
                 ">= 1, --grid 16..512\n",
                 args.error().empty() ? size_list.c_str() : args.error().c_str());
    return 2;
  }
  const SkyExtent sky{grid, int(args.getInt("sky-span", kDefaultSkySpan))};
  if (const std::string problem = sky.check(); !problem.empty()) {
    std::fprintf(stderr, "cloudbrush bench scale: --sky-span: %s\n", problem.c_str());
    return 2;
  }
  const std::string parts = args.get("parts", "all");
  if (parts.find_first_of("'\" ;") != std::string::npos) {
    std::fprintf(stderr, "cloudbrush bench scale: --parts: all, or orbit,pen,actions\n");
    return 2;
  }
  if (args.has("child")) return runChild(sizes, frames, sky, args.has("quick"), parts);

  std::vector<int> threads, spans;
  if (!parseIntList(args.get("threads", "1,2"), 1, 64, &threads)) {
    std::fprintf(stderr, "cloudbrush bench scale: --threads: expected 1..64, ...\n");
    return 2;
  }
  if (!parseIntList(args.get("sky-spans", "1,2,4"), 0, kMaxSkySpan, &spans)) {
    std::fprintf(stderr, "cloudbrush bench scale: --sky-spans: expected 0..%d, ...\n", kMaxSkySpan);
    return 2;
  }
  spans.erase(std::remove(spans.begin(), spans.end(), 0), spans.end());
  std::error_code ec;
  const ChildRunner runner{std::filesystem::read_symlink("/proc/self/exe", ec).string(), frames,
                           grid, parts};
  if (ec) {
    std::fprintf(stderr, "cloudbrush bench scale: cannot find this binary (%s)\n",
                 ec.message().c_str());
    return 1;
  }
  BenchReport report("scale");
  noteLoadAverage(report);
  std::printf("bench scale: sizes %s, threads", size_list.c_str());
  for (int t : threads) std::printf(" %d", t);
  std::printf(
      ", the bundled cumulus %d^3 in a sky of %d x %d home boxes (each thread count in a child "
      "process)\n",
      grid, sky.span, sky.span);

  ThreadFigures f;
  for (int t : threads) {
    std::printf("threads %d:\n", t);
    std::fflush(stdout);
    runner.run(t, size_list, sky.span, false, &f.figures[t], &f.baselines[t]);
  }
  printSizeTable(report, sizes, threads, f);
  if (std::find(threads.begin(), threads.end(), 2) != threads.end() &&
      std::any_of(sizes.begin(), sizes.end(),
                  [](const Size& s) { return s.name() == "1920x1080"; }))
    printTargets(f);
  printPersonTable(report, threads, f);
  if (!spans.empty()) benchSkySizes(report, runner, threads, spans);
  report.print();
  return 0;
}

}  // namespace cb
