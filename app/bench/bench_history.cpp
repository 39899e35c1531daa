// `cloudbrush bench history` ("History"): undo/redo of a stroke at 1280×720 on the
// product's defaults (256³ sky, default brush and mapping config, the default paint view), each
// timed from the command's dispatch: → volume and light volume restored (History + the
// renderer's sync), → glFinish of the first full-resolution frame that shows it. Also the bytes
// held by the history after N strokes (compressed brick deltas + the committed copy) with the
// process's RSS growth, and erase / light changes → lit frame.
//
// Baseline, measured in the same run: the thesis's method (§3.3), a whole-volume zlib snapshot
// per step — its compress time, size, and restore (uncompress + full light recompute + frame).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <zlib.h>

#include "app/bench/bench_report.h"
#include "app/bench/benches.h"
#include "app/cli/args.h"
#include "app/core/config_paths.h"
#include "app/render/gl/egl_context.h"
#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"
#include "app/session/paint_session.h"
#include "app/session/synthetic_session.h"

namespace cb {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

int benchHistory(int argc, char** argv) {
  Args args(argc, argv, {"help"});
  if (args.has("help")) {
    std::printf(
        "usage: cloudbrush bench history [--strokes N] [--size WxH] [--grid N]\n"
        "Paints N strokes (default 200) across the default paint view, then times undo/redo,\n"
        "erase and light changes to a restored volume + light volume and to the first lit\n"
        "frame; prints history bytes and RSS; baseline: whole-volume zlib snapshots.\n");
    return 0;
  }
  const int strokes = int(args.getInt("strokes", 200));
  const int grid = int(args.getInt("grid", 256));
  const int w = 1280, h = 720;
  if (!args.error().empty() || strokes < 1 || grid < 16) {
    std::fprintf(stderr, "cloudbrush bench history: %s\n",
                 args.error().empty() ? "--strokes >= 1, --grid >= 16" : args.error().c_str());
    return 2;
  }
  EglContext context;
  std::string error;
  if (!createSurfacelessContext(&context, &error)) {
    std::fprintf(stderr, "cloudbrush bench history: %s\n", error.c_str());
    return 1;
  }
  VolumeRenderer renderer;
  RenderTarget target;
  if (!renderer.init(&error) || !target.create(w, h, RenderTarget::Format::kRgba8, &error)) {
    std::fprintf(stderr, "cloudbrush bench history: %s\n", error.c_str());
    return 1;
  }
  MappingConfig mapping;
  try {
    mapping = loadMappingConfig(configFile("mapping.toml"));
  } catch (const std::exception&) {
  }
  PaintSession session({w, h, grid}, loadDefaultBrushConfig(), mapping);
  session.setQuietMapping(true);
  const PenDeviceInfo tablet = syntheticTablet(w, h);
  session.setDevice(tablet, 0);
  const auto frame = [&]() {
    renderer.render(session.camera(), w, h, target.fbo());
    glFinish();
  };
  renderer.sync(session.volume(), session.light());
  frame();
  const double rss_before = processRssMb();

  // N strokes: the reference strokes shifted over a grid of places in the drawable region.
  std::printf("painting %d strokes at %dx%d into %d³ ...\n", strokes, w, h, grid);
  const std::vector<SyntheticStroke> base = referencePaintStrokes(w, h);
  int64_t t = 1'000'000'000;
  const auto paint_start = Clock::now();
  for (int i = 0; i < strokes; ++i) {
    SyntheticStroke s = base[size_t(i) % base.size()];
    const glm::vec2 shift(float((i * 37) % 9 - 4) * 0.05f * w, float((i * 53) % 7 - 3) * 0.05f * h);
    for (glm::vec2& p : s.control_points) p += shift;
    for (const PenSample& sample : syntheticPenSamples(s, tablet, w, h, 200.0, t)) {
      session.feed(sample);
      t = sample.t_ns;
    }
    t += 100'000'000;
    renderer.sync(session.volume(), session.light());
  }
  const double paint_s = msSince(paint_start) / 1000.0;
  const History& history = session.history();
  const double delta_mb = double(history.deltaBytes()) / (1 << 20);
  const double copy_mb = double(history.copyBytes()) / (1 << 20);
  const double rss_growth = processRssMb() - rss_before;
  std::printf(
      "%u strokes mapped in %.1f s; history: %zu steps, deltas %.1f MB + committed copy "
      "%.1f MB = %.1f MB; RSS growth %.1f MB\n",
      session.strokesMapped(), paint_s, history.steps(), delta_mb, copy_mb, delta_mb + copy_mb,
      rss_growth);

  // Undo and redo, each timed from the dispatch of the command.
  std::vector<double> undo_ready, undo_frame, redo_ready, redo_frame;
  for (int i = 0; i < 10; ++i) {
    for (bool undo : {true, false}) {
      const auto start = Clock::now();
      if (!session.apply(undo ? UiChange(ui::Undo{}) : UiChange(ui::Redo{}), t, &error)) {
        std::fprintf(stderr, "cloudbrush bench history: %s\n", error.c_str());
        return 1;
      }
      renderer.sync(session.volume(), session.light());
      (undo ? undo_ready : redo_ready).push_back(msSince(start));
      frame();
      (undo ? undo_frame : redo_frame).push_back(msSince(start));
    }
  }
  // Erase (a vacuum cut at the scene's centre) and a light change, to the lit frame.
  // A light-ball drag frame (the light volume swept at half resolution per axis, as the painter
  // does while dragging) and the release frame after it (the full sweep), beside the full-
  // resolution light change measured the same way.
  std::vector<double> erase_frame, light_frame, light_drag_frame, light_release_frame;
  std::vector<double> light_sweep_ms, light_drag_sweep_ms;
  std::vector<double> light_sync_cpu_ms, light_drag_sync_cpu_ms;  // CPU of all threads (load-proof)
  for (int i = 0; i < 9; ++i) {
    auto start = Clock::now();
    session.apply(ui::VacuumCut{glm::vec3(0.1f * float(i - 2), 0.0f, 0.0f), 0.15f}, t, &error);
    renderer.sync(session.volume(), session.light());
    frame();
    erase_frame.push_back(msSince(start));
    start = Clock::now();
    const Light l = session.light();
    session.apply(
        ui::SetLight{glm::normalize(l.direction + glm::vec3(0.05f, 0.0f, 0.0f)), l.colour}, t,
        &error);
    double cpu0 = processCpuMs();
    light_sweep_ms.push_back(renderer.sync(session.volume(), session.light()).light_ms);
    light_sync_cpu_ms.push_back(processCpuMs() - cpu0);
    frame();
    light_frame.push_back(msSince(start));

    renderer.setLightPreviewDivisor(2);
    start = Clock::now();
    const Light m = session.light();
    session.apply(
        ui::SetLight{glm::normalize(m.direction + glm::vec3(0.0f, 0.0f, 0.05f)), m.colour}, t,
        &error);
    cpu0 = processCpuMs();
    light_drag_sweep_ms.push_back(renderer.sync(session.volume(), session.light()).light_ms);
    light_drag_sync_cpu_ms.push_back(processCpuMs() - cpu0);
    frame();
    light_drag_frame.push_back(msSince(start));
    renderer.setLightPreviewDivisor(1);
    start = Clock::now();
    renderer.sync(session.volume(), session.light());
    frame();
    light_release_frame.push_back(msSince(start));
  }

  // Baseline: the thesis's whole-volume zlib snapshot per step.
  const Volume& volume = session.volume();
  const std::vector<float> dense = volume.toDense();  // the thesis kept the dense grid
  const uLong raw = uLong(dense.size() * sizeof(float));
  std::vector<Bytef> packed(compressBound(raw));
  uLongf packed_size = packed.size();
  auto start = Clock::now();
  compress2(packed.data(), &packed_size, reinterpret_cast<const Bytef*>(dense.data()), raw, 6);
  const double zlib_snapshot_ms = msSince(start);
  Volume restored = volume;
  start = Clock::now();
  uLongf out_size = raw;
  std::vector<float> unpacked(dense.size());
  uncompress(reinterpret_cast<Bytef*>(unpacked.data()), &out_size, packed.data(), packed_size);
  restored.assignDense(unpacked.data());
  renderer.sync(restored, session.light());
  const double zlib_ready_ms = msSince(start);
  renderer.render(session.camera(), w, h, target.fbo());
  glFinish();
  const double zlib_frame_ms = msSince(start);
  const double zlib_mb_per_step = double(packed_size) / (1 << 20);

  std::printf(
      "undo → volume + light restored: median %.1f ms (max %.1f); → first lit frame "
      "%.1f ms (target ≤ 50 / ≤ 200)\n",
      median(undo_ready), *std::max_element(undo_ready.begin(), undo_ready.end()),
      median(undo_frame));
  std::printf("redo → restored %.1f ms; → first lit frame %.1f ms\n", median(redo_ready),
              median(redo_frame));
  std::printf("erase (vacuum) → lit frame %.1f ms; light change → lit frame %.1f ms (≤ 200)\n",
              median(erase_frame), median(light_frame));
  std::printf(
      "light drag frame (light volume at 1/2 per axis) %.1f ms, its sweep %.1f ms, sync CPU %.1f "
      "ms; full sweep %.1f ms, sync CPU %.1f ms; release → full lit frame %.1f ms\n",
      median(light_drag_frame), median(light_drag_sweep_ms), median(light_drag_sync_cpu_ms),
      median(light_sweep_ms), median(light_sync_cpu_ms), median(light_release_frame));
  std::printf(
      "history after %d strokes: %.1f MB (target ≤ 256 MB); zlib snapshots would hold "
      "%.1f MB (%.1f MB each)\n",
      strokes, delta_mb + copy_mb, zlib_mb_per_step * strokes, zlib_mb_per_step);
  std::printf(
      "baseline zlib: snapshot %.1f ms per step, restore → ready %.1f ms, → frame %.1f "
      "ms\n",
      zlib_snapshot_ms, zlib_ready_ms, zlib_frame_ms);

  BenchReport report("history");
  report.figure("undo_restored_ms", median(undo_ready));
  report.figure("undo_first_frame_ms", median(undo_frame));
  report.figure("redo_restored_ms", median(redo_ready));
  report.figure("redo_first_frame_ms", median(redo_frame));
  report.figure("erase_lit_frame_ms", median(erase_frame));
  report.figure("light_lit_frame_ms", median(light_frame));
  report.figure("light_drag_frame_ms", median(light_drag_frame));
  report.figure("light_drag_sweep_ms", median(light_drag_sweep_ms));
  report.figure("light_release_frame_ms", median(light_release_frame));
  report.figure("light_drag_sync_cpu_ms", median(light_drag_sync_cpu_ms));
  report.baseline("light_sync_cpu_ms", median(light_sync_cpu_ms));
  report.baseline("light_full_sweep_ms", median(light_sweep_ms));
  report.figure("history_mb", delta_mb + copy_mb);
  report.figure("history_delta_mb", delta_mb);
  report.figure("rss_growth_mb", rss_growth);
  report.figure("strokes", strokes);
  report.baseline("zlib_snapshot_ms", zlib_snapshot_ms);
  report.baseline("zlib_restore_ready_ms", zlib_ready_ms);
  report.baseline("zlib_restore_frame_ms", zlib_frame_ms);
  report.baseline("zlib_history_mb", zlib_mb_per_step * strokes);
  report.print();
  return 0;
}

}  // namespace cb
