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

// The painter's session on a renderer with its target, and the journal clock.
struct HistoryBench {
  HistoryBench(VolumeRenderer& r, RenderTarget& tg, PaintSession& s, int width, int height)
      : renderer(r), target(tg), session(s), w(width), h(height) {}
  VolumeRenderer& renderer;
  RenderTarget& target;
  PaintSession& session;
  int w, h;
  int64_t t = 1'000'000'000;
  std::string error;

  void frame() {
    renderer.render(session.camera(), w, h, target.fbo());
    glFinish();
  }
  void sync() { renderer.sync(session.volume(), session.light()); }
};

// N strokes: the reference strokes shifted over a grid of places in the drawable region, each
// synced. The seconds they took.
double paintStrokes(HistoryBench& b, const PenDeviceInfo& tablet, int strokes) {
  const std::vector<SyntheticStroke> base = referencePaintStrokes(b.w, b.h);
  const auto paint_start = Clock::now();
  for (int i = 0; i < strokes; ++i) {
    SyntheticStroke s = base[size_t(i) % base.size()];
    const glm::vec2 shift(float((i * 37) % 9 - 4) * 0.05f * b.w,
                          float((i * 53) % 7 - 3) * 0.05f * b.h);
    for (glm::vec2& p : s.control_points) p += shift;
    for (const PenSample& sample : syntheticPenSamples(s, tablet, b.w, b.h, 200.0, b.t)) {
      b.session.feed(sample);
      b.t = sample.t_ns;
    }
    b.t += 100'000'000;
    b.sync();
  }
  return msSince(paint_start) / 1000.0;
}

struct UndoRedoTimes {
  std::vector<double> undo_ready, undo_frame, redo_ready, redo_frame;
};

// Undo and redo, each timed from the dispatch of the command. False with b.error on failure.
bool timeUndoRedo(HistoryBench& b, UndoRedoTimes* out) {
  for (int i = 0; i < 10; ++i) {
    for (bool undo : {true, false}) {
      const auto start = Clock::now();
      if (!b.session.apply(undo ? UiChange(ui::Undo{}) : UiChange(ui::Redo{}), b.t, &b.error))
        return false;
      b.sync();
      (undo ? out->undo_ready : out->redo_ready).push_back(msSince(start));
      b.frame();
      (undo ? out->undo_frame : out->redo_frame).push_back(msSince(start));
    }
  }
  return true;
}

struct EraseLightTimes {
  std::vector<double> erase_frame, light_frame, light_drag_frame, light_release_frame;
  std::vector<double> light_sweep_ms, light_drag_sweep_ms;
  std::vector<double> light_sync_cpu_ms, light_drag_sync_cpu_ms;  // CPU of all threads
};

// Erase (a vacuum cut at the scene's centre) and a light change, to the lit frame. A light-ball
// drag frame (the light swept at half resolution per axis into the preview texture, as the
// painter does while dragging) and the release frame after it (the full sweep), beside the
// full-resolution light change measured the same way.
EraseLightTimes timeEraseAndLight(HistoryBench& b) {
  EraseLightTimes r;
  PaintSession& session = b.session;
  for (int i = 0; i < 9; ++i) {
    auto start = Clock::now();
    session.apply(ui::VacuumCut{glm::vec3(0.1f * float(i - 2), 0.0f, 0.0f), 0.15f}, b.t, &b.error);
    b.sync();
    b.frame();
    r.erase_frame.push_back(msSince(start));
    start = Clock::now();
    const Light l = session.light();
    session.apply(
        ui::SetLight{glm::normalize(l.direction + glm::vec3(0.05f, 0.0f, 0.0f)), l.colour}, b.t,
        &b.error);
    double cpu0 = processCpuMs();
    r.light_sweep_ms.push_back(b.renderer.sync(session.volume(), session.light()).light_ms);
    r.light_sync_cpu_ms.push_back(processCpuMs() - cpu0);
    b.frame();
    r.light_frame.push_back(msSince(start));

    b.renderer.setLightPreviewDivisor(2);
    start = Clock::now();
    const Light m = session.light();
    session.apply(
        ui::SetLight{glm::normalize(m.direction + glm::vec3(0.0f, 0.0f, 0.05f)), m.colour}, b.t,
        &b.error);
    cpu0 = processCpuMs();
    r.light_drag_sweep_ms.push_back(b.renderer.sync(session.volume(), session.light()).light_ms);
    r.light_drag_sync_cpu_ms.push_back(processCpuMs() - cpu0);
    b.frame();
    r.light_drag_frame.push_back(msSince(start));
    b.renderer.setLightPreviewDivisor(1);
    start = Clock::now();
    b.sync();
    b.frame();
    r.light_release_frame.push_back(msSince(start));
  }
  return r;
}

struct ZlibBaseline {
  double snapshot_ms = 0, ready_ms = 0, frame_ms = 0, mb_per_step = 0;
};

// Baseline: the thesis's whole-volume zlib snapshot per step, and its restore (uncompress +
// full light recompute + frame).
ZlibBaseline timeZlibSnapshot(HistoryBench& b) {
  ZlibBaseline z;
  const Volume& volume = b.session.volume();
  const std::vector<float> dense = volume.toDense();  // the thesis kept the dense grid
  const uLong raw = uLong(dense.size() * sizeof(float));
  std::vector<Bytef> packed(compressBound(raw));
  uLongf packed_size = packed.size();
  auto start = Clock::now();
  compress2(packed.data(), &packed_size, reinterpret_cast<const Bytef*>(dense.data()), raw, 6);
  z.snapshot_ms = msSince(start);
  Volume restored = volume;
  start = Clock::now();
  uLongf out_size = raw;
  std::vector<float> unpacked(dense.size());
  uncompress(reinterpret_cast<Bytef*>(unpacked.data()), &out_size, packed.data(), packed_size);
  restored.assignDense(unpacked.data());
  b.renderer.sync(restored, b.session.light());
  z.ready_ms = msSince(start);
  b.renderer.render(b.session.camera(), b.w, b.h, b.target.fbo());
  glFinish();
  z.frame_ms = msSince(start);
  z.mb_per_step = double(packed_size) / (1 << 20);
  return z;
}

void printHistoryFigures(const UndoRedoTimes& u, const EraseLightTimes& e, const ZlibBaseline& z,
                         int strokes, double history_mb) {
  std::printf(
      "undo → volume + light restored: median %.1f ms (max %.1f); → first lit frame "
      "%.1f ms (target ≤ 50 / ≤ 200)\n",
      median(u.undo_ready), *std::max_element(u.undo_ready.begin(), u.undo_ready.end()),
      median(u.undo_frame));
  std::printf("redo → restored %.1f ms; → first lit frame %.1f ms\n", median(u.redo_ready),
              median(u.redo_frame));
  std::printf("erase (vacuum) → lit frame %.1f ms; light change → lit frame %.1f ms (≤ 200)\n",
              median(e.erase_frame), median(e.light_frame));
  std::printf(
      "light drag frame (the coarse light at 1/2 per axis) %.1f ms, its sweep %.1f ms, sync CPU %.1f "
      "ms; full sweep %.1f ms, sync CPU %.1f ms; release → full lit frame %.1f ms\n",
      median(e.light_drag_frame), median(e.light_drag_sweep_ms), median(e.light_drag_sync_cpu_ms),
      median(e.light_sweep_ms), median(e.light_sync_cpu_ms), median(e.light_release_frame));
  std::printf(
      "history after %d strokes: %.1f MB (target ≤ 256 MB); zlib snapshots would hold "
      "%.1f MB (%.1f MB each)\n",
      strokes, history_mb, z.mb_per_step * strokes, z.mb_per_step);
  std::printf(
      "baseline zlib: snapshot %.1f ms per step, restore → ready %.1f ms, → frame %.1f "
      "ms\n",
      z.snapshot_ms, z.ready_ms, z.frame_ms);
}

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
  HistoryBench b(renderer, target, session, w, h);
  b.sync();
  b.frame();
  const double rss_before = processRssMb();

  std::printf("painting %d strokes at %dx%d into %d³ ...\n", strokes, w, h, grid);
  const double paint_s = paintStrokes(b, tablet, strokes);
  const History& history = session.history();
  const double delta_mb = double(history.deltaBytes()) / (1 << 20);
  const double copy_mb = double(history.copyBytes()) / (1 << 20);
  const double rss_growth = processRssMb() - rss_before;
  std::printf(
      "%u strokes mapped in %.1f s; history: %zu steps, deltas %.1f MB + committed copy "
      "%.1f MB = %.1f MB; RSS growth %.1f MB\n",
      session.strokesMapped(), paint_s, history.steps(), delta_mb, copy_mb, delta_mb + copy_mb,
      rss_growth);

  UndoRedoTimes u;
  if (!timeUndoRedo(b, &u)) {
    std::fprintf(stderr, "cloudbrush bench history: %s\n", b.error.c_str());
    return 1;
  }
  const EraseLightTimes e = timeEraseAndLight(b);
  const ZlibBaseline z = timeZlibSnapshot(b);
  printHistoryFigures(u, e, z, strokes, delta_mb + copy_mb);

  BenchReport report("history");
  report.figure("undo_restored_ms", median(u.undo_ready));
  report.figure("undo_first_frame_ms", median(u.undo_frame));
  report.figure("redo_restored_ms", median(u.redo_ready));
  report.figure("redo_first_frame_ms", median(u.redo_frame));
  report.figure("erase_lit_frame_ms", median(e.erase_frame));
  report.figure("light_lit_frame_ms", median(e.light_frame));
  report.figure("light_drag_frame_ms", median(e.light_drag_frame));
  report.figure("light_drag_sweep_ms", median(e.light_drag_sweep_ms));
  report.figure("light_release_frame_ms", median(e.light_release_frame));
  report.figure("light_drag_sync_cpu_ms", median(e.light_drag_sync_cpu_ms));
  report.baseline("light_sync_cpu_ms", median(e.light_sync_cpu_ms));
  report.baseline("light_full_sweep_ms", median(e.light_sweep_ms));
  report.figure("history_mb", delta_mb + copy_mb);
  report.figure("history_delta_mb", delta_mb);
  report.figure("rss_growth_mb", rss_growth);
  report.figure("strokes", strokes);
  report.baseline("zlib_snapshot_ms", z.snapshot_ms);
  report.baseline("zlib_restore_ready_ms", z.ready_ms);
  report.baseline("zlib_restore_frame_ms", z.frame_ms);
  report.baseline("zlib_history_mb", z.mb_per_step * strokes);
  report.print();
  return 0;
}

}  // namespace cb
