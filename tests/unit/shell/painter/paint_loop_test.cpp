// The interactive painting path without hardware: a recorded synthetic stroke played by the
// replay pen backend into PaintLoop on the surfaceless display (EGL on llvmpipe), 1280×720.
// Checks that the live footprint is on screen before the lift, that the lift maps voxels inside
// the reported dirty box only, and that the first lit frame shows the cloud where the ink was.
// Prints the pen-up -> first lit frame time (target <= 200 ms).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "app/render/image_io.h"
#include "app/scene/drawable_region.h"
#include "app/session/paint_session.h"
#include "app/session/synthetic_session.h"
#include "app/shell/painter/paint_loop.h"
#include "app/shell/painter/paint_screen.h"
#include "drivers/open_pen_source.h"
#include "drivers/replay/replay_pen_source.h"
#include "tests/support/test_display.h"

namespace cb {
namespace {

constexpr int kW = 1280, kH = 720, kGrid = 128;

std::string tempDir() {
  const auto dir =
      std::filesystem::temp_directory_path() / ("cb_paint_loop_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir.string();
}

// Writes a journal of `strokes` drawn on a w×h screen, half a second apart, to `path`.
std::string writeStrokeJournal(const std::string& path, const std::vector<SyntheticStroke>& strokes,
                               int w, int h) {
  PaintSession recorder({w, h, 32}, BrushConfig{}, MappingConfig{});
  recorder.setQuietMapping(true);
  JournalWriter journal;
  EXPECT_TRUE(journal.open(path)) << journal.error();
  recorder.recordTo(&journal, 0);
  const PenDeviceInfo tablet = syntheticTablet(w, h);
  recorder.setDevice(tablet, 0);
  int64_t t0 = 1'000'000'000;
  for (const SyntheticStroke& stroke : strokes) {
    const std::vector<PenSample> samples = syntheticPenSamples(stroke, tablet, w, h, 200.0, t0);
    for (const PenSample& s : samples) recorder.feed(s);
    t0 = samples.back().t_ns + 500'000'000;
  }
  EXPECT_EQ(recorder.strokesMapped(), strokes.size());
  return path;
}

// Pixels whose colour differs by more than `threshold` in any channel.
// Pixels of the scene that may show the cloud: inside the drawable region (outside it the pen's
// veil comes and goes with proximity) and below the status line.
std::vector<uint8_t> g_scene_mask;

long changedPixels(const ImageRgba8& a, const ImageRgba8& b, int threshold) {
  long n = 0;
  for (size_t i = 0; i + 3 < a.pixels.size(); i += 4)
    for (int c = 0; c < 3 && (g_scene_mask.empty() || g_scene_mask[i / 4]); ++c)
      if (std::abs(int(a.pixels[i + c]) - int(b.pixels[i + c])) > threshold) {
        ++n;
        break;
      }
  return n;
}

struct Frames {
  ImageRgba8 before_stroke, during_stroke, first_lit;
  bool have_before = false, have_during = false, have_lit = false;
  long ink_frames = 0;  // frames drawn during the stroke with footprint texels uploaded
  double pen_up_to_lit_ms = 0.0;
  std::array<double, 4> parts{};  // mapping, sync, render, composite
  ImageRgba8 refined;             // the next frame, at full resolution
  double pen_up_to_refined_ms = 0.0;
  long long lit_pixels = 0, refined_pixels = 0;  // ray cast for those two frames
  float lit_scale = 0.0f;
};

// The voxels the stroke wrote (non-zero ones) all lie inside the box the volume reports as
// changed since `since`; returns how many.
long expectWritesInsideTheDirtyBox(const Volume& volume, uint64_t since) {
  const VoxelBox dirty = volume.dirtySince(since);
  long inside = 0, outside = 0;
  for (const glm::ivec3& b : volume.allocatedBrickList()) {
    const VoxelBox box = volume.brickBox(b);
    for (int z = box.lo.z; z < box.hi.z; ++z)
      for (int y = box.lo.y; y < box.hi.y; ++y)
        for (int x = box.lo.x; x < box.hi.x; ++x) {
          if (volume.at(x, y, z) == 0.0f) continue;
          const bool in = x >= dirty.lo.x && y >= dirty.lo.y && z >= dirty.lo.z && x < dirty.hi.x &&
                          y < dirty.hi.y && z < dirty.hi.z;
          ++(in ? inside : outside);
        }
  }
  EXPECT_GT(inside, 1000);
  EXPECT_EQ(outside, 0);
  return inside;
}

// Pixels (in the scene, not under the status line) where both the lit frame and the frame
// during the stroke differ from the sky before it: cloud where the ink was.
long cloudOnInk(const Frames& frames) {
  long n = 0;
  for (size_t i = 0; i + 3 < frames.first_lit.pixels.size(); i += 4) {
    const auto differs = [&](const ImageRgba8& image, int threshold) {
      for (int c = 0; c < 3; ++c)
        if (std::abs(int(image.pixels[i + c]) - int(frames.before_stroke.pixels[i + c])) >
            threshold)
          return true;
      return false;
    };
    n += (g_scene_mask.empty() || g_scene_mask[i / 4]) && differs(frames.first_lit, 8) &&
         differs(frames.during_stroke, 24);
  }
  return n;
}

// The pen-up path re-renders only the pixels whose rays cross what the stroke changed
// (changed_region.h), at the reduced scale and then at full resolution; its parts are timed.
void expectPenUpPathTimedAndSmall(const Frames& frames, const PaintLoopSummary& summary,
                                  const Display& display) {
  const long long reduced_frame =
      (long long)std::lround(kW * frames.lit_scale) * std::lround(kH * frames.lit_scale);
  std::printf("pixels ray cast: lit frame %lld of %lld (scale %.2f), refined %lld of %d\n",
              frames.lit_pixels, reduced_frame, double(frames.lit_scale), frames.refined_pixels,
              kW * kH);
  EXPECT_GE(frames.lit_scale, 0.5f);
  EXPECT_LT(frames.lit_scale, 1.0f);
  EXPECT_GT(frames.lit_pixels, 0);
  EXPECT_LT(frames.lit_pixels, reduced_frame);
  EXPECT_GT(frames.refined_pixels, 0);
  EXPECT_LT(frames.refined_pixels, (long long)kW * kH);
  EXPECT_GT(summary.painting_frames, 20);
  std::printf("painting: median %.2f ms/frame over %ld frames while drawing (target <= 16.7)\n",
              summary.median_painting_frame_ms, summary.painting_frames);
  std::printf(
      "pen-up -> first lit frame (at the moving scale 0.5): %.1f ms (mapping %.1f, sync %.1f, "
      "ray cast %.1f, to the display %.1f) at %dx%d, grid %d³ on %s (target <= 200 ms)\n",
      frames.pen_up_to_lit_ms, frames.parts[0], frames.parts[1], frames.parts[2], frames.parts[3],
      kW, kH, kGrid, display.context().renderer.c_str());
  // The parts after the mapping (sync, ray cast, to the display) lie inside the pen-up -> lit
  // time. The mapping itself is no longer always inside it: with the ink latched late in the
  // frame, the lift can be mapped before the timer the figure reads starts (measured: mapping
  // 4.9 ms outside a 53.5 ms total). Known; the journal's Frame records time from the sample.
  EXPECT_GE(frames.parts[0], 0.0);
  EXPECT_LE(frames.parts[1] + frames.parts[2] + frames.parts[3], frames.pen_up_to_lit_ms + 0.5);
}

TEST(PaintLoop, StrokeShowsLiveThenAsALitCloud) {
  const std::string dir = tempDir();
  // One reference stroke (the S curve) at this screen size.
  const std::string journal =
      writeStrokeJournal(dir + "/stroke.cbj", {gentleCurve(kW, kH)}, kW, kH);

  std::string error;
  std::unique_ptr<Display> display = test::openTestDisplay(kW, kH, &error);
  ASSERT_TRUE(display) << error;
  VolumeRenderer renderer;
  ASSERT_TRUE(renderer.init(&error)) << error;

  PaintSession session({kW, kH, kGrid}, BrushConfig{}, MappingConfig{});
  session.setQuietMapping(true);
  const uint64_t empty_generation = session.volume().generation();
  {
    const DrawableRegion region(session.camera(), session.canvas(), session.volume().worldMin(),
                                session.volume().worldMax(), kW, kH);
    g_scene_mask = region.mask();
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < kW; ++x) g_scene_mask[size_t(y) * kW + size_t(x)] = 0;
  }
  ReplayOptions replay_options;
  replay_options.realtime = false;
  replay_options.batch = 4;  // ~20 ms of samples per frame, as a 200 Hz pen at 50 fps
  ReplayPenSource pen(journal, replay_options);
  ASSERT_GT(pen.sampleCount(), 100u);

  Frames frames;
  PaintLoopOptions options;
  options.max_frames = 2000;
  options.config_dir = dir + "/config";  // nothing there: built-in calibration defaults
  options.state_dir = dir + "/state";
  options.on_frame = [&](const PaintFrameInfo& info) {
    if (!info.painting_view) return;
    if (!frames.have_before && !info.in_stroke) {
      frames.before_stroke = readFramebufferRgba8(display->framebuffer(), kW, kH);
      frames.have_before = true;
    }
    if (info.in_stroke && info.texels_uploaded > 0) {
      ++frames.ink_frames;
      frames.during_stroke = readFramebufferRgba8(display->framebuffer(), kW, kH);
      frames.have_during = true;
    }
    if (info.refined_after_lift) {
      frames.refined = readFramebufferRgba8(display->framebuffer(), kW, kH);
      frames.pen_up_to_refined_ms = info.pen_up_to_refined_ms;
      frames.refined_pixels = info.rendered_pixels;
    }
    if (info.first_lit_after_lift) {
      frames.first_lit = readFramebufferRgba8(display->framebuffer(), kW, kH);
      frames.have_lit = true;
      frames.pen_up_to_lit_ms = info.pen_up_to_lit_ms;
      frames.parts = {info.mapping_ms, info.sync_ms, info.render_ms, info.composite_ms};
      frames.lit_pixels = info.rendered_pixels;
      frames.lit_scale = info.render_scale;
    }
  };
  const Light light;
  PaintLoop loop(*display, renderer, session.volume(), light, options);
  loop.attachPen(&pen, &session);
  PaintLoopSummary summary;
  ASSERT_TRUE(loop.run(nullptr, &summary, &error)) << error;
  EXPECT_EQ(summary.quit_reason, "replay finished");
  EXPECT_EQ(summary.pen_samples, long(pen.sampleCount()));
  ASSERT_EQ(summary.strokes_mapped, 1);
  ASSERT_TRUE(frames.have_before && frames.have_during && frames.have_lit);

  // Live: many frames carried new ink, and the last one shows the footprint over the scene.
  EXPECT_GT(frames.ink_frames, 20);
  const long ink = changedPixels(frames.before_stroke, frames.during_stroke, 24);
  EXPECT_GT(ink, 5000) << "footprint pixels visible before the lift";

  // Mapped: voxels were written, all inside the box the volume reports as changed.
  const long inside = expectWritesInsideTheDirtyBox(session.volume(), empty_generation);

  // Lit: the cloud is on screen where there was only sky, and the ink overlay is gone.
  const long cloud = changedPixels(frames.before_stroke, frames.first_lit, 8);
  EXPECT_GT(cloud, 5000) << "pixels changed by the lit cloud";
  EXPECT_GT(changedPixels(frames.during_stroke, frames.first_lit, 24), 1000);
  // ... and the cloud lies under the ink (both differ from the sky at the same pixels).
  const long cloud_on_ink = cloudOnInk(frames);
  // Where the ink was, there is cloud; and the cloud is not somewhere else. At this test's 128³
  // a 30-px stroke is 3 voxels wide: the spheres are widened so they are opaque out to the ink
  // (app/mapping/README.md, outline_chord_voxels), which leaves a faint halo about a voxel
  // (~10 px) wide on each side that this any-visible-change count includes. Measured: the
  // whole ink shows cloud, 48 % of the changed pixels lie on the ink (61 % before the
  // widening, when the rim was translucent).
  EXPECT_GT(cloud_on_ink, ink * 9 / 10) << "the ink should show cloud";
  EXPECT_GT(cloud_on_ink, cloud * 2 / 5) << "most cloud pixels should be near where the ink was";

  std::printf(
      "ink frames %ld, ink pixels %ld, voxels %ld in the dirty box, cloud pixels %ld "
      "(%ld under the ink)\n",
      frames.ink_frames, ink, inside, cloud, cloud_on_ink);
  if (const char* keep = std::getenv("CB_PAINT_LOOP_KEEP_FRAMES")) {  // for looking at them
    writePng(std::string(keep) + "/during_stroke.png", frames.during_stroke);
    writePng(std::string(keep) + "/first_lit.png", frames.first_lit);
    std::filesystem::copy_file(journal, std::string(keep) + "/stroke.cbj",
                               std::filesystem::copy_options::overwrite_existing);
  }
  ASSERT_EQ(summary.pen_up_to_lit_ms.size(), 1u);
  // The full-resolution refinement follows and shows the same cloud, sharper.
  ASSERT_EQ(summary.pen_up_to_refined_ms.size(), 1u);
  ASSERT_EQ(frames.refined.pixels.size(), frames.first_lit.pixels.size());
  const long refined_cloud = changedPixels(frames.before_stroke, frames.refined, 8);
  EXPECT_GT(refined_cloud, cloud / 2);
  EXPECT_LT(refined_cloud, cloud * 2);
  std::printf("pen-up -> full-resolution lit frame: %.1f ms\n", frames.pen_up_to_refined_ms);
  expectPenUpPathTimedAndSmall(frames, summary, *display);
  RecordProperty("pen_up_to_lit_ms", std::to_string(frames.pen_up_to_lit_ms));
  std::filesystem::remove_all(dir);
}

// No tablet is a state, not an exit: with a searching pen source the painter shows its paint
// view, ready for the mouse, and says so (not an orbit of the bundled cloud).
TEST(PaintLoop, MissingTabletShowsThePaintViewReadyForTheMouse) {
  std::string error;
  std::unique_ptr<Display> display = test::openTestDisplay(320, 180, &error);
  ASSERT_TRUE(display) << error;
  VolumeRenderer renderer;
  ASSERT_TRUE(renderer.init(&error)) << error;
  PenSourceOptions pen_options;
  pen_options.backend = "evdev";
  pen_options.device = "/nonexistent/cloudbrush-pen";
  std::unique_ptr<PenSource> pen = openPenSource(pen_options, &error);
  ASSERT_TRUE(pen) << error;
  EXPECT_NE(pen->connection(), PenConnection::kConnected);
  PaintSession session({320, 180, 16}, BrushConfig{}, MappingConfig{});
  PaintLoopOptions options;
  options.max_frames = 5;
  long painting_frames = 0;
  options.on_frame = [&](const PaintFrameInfo& info) { painting_frames += info.painting_view; };
  PaintLoop loop(*display, renderer, session.volume(), Light{}, options);
  loop.attachPen(pen.get(), &session);
  PaintLoopSummary summary;
  ASSERT_TRUE(loop.run(nullptr, &summary, &error)) << error;
  EXPECT_EQ(summary.quit_reason, "frame limit");
  EXPECT_EQ(painting_frames, 5);
  EXPECT_NE(loop.screen().statusLine().find("mouse"), std::string::npos)
      << loop.screen().statusLine();
  EXPECT_FALSE(loop.screen().hint().empty()) << "the first screen says how to paint";
}

// After a lift the change is shown at the moving scale and then refined, unless the cost per
// pixel of the last full-resolution frames says it fits the pen-up budget: then the first lit
// frame is already at full resolution and is also the refined one. Two strokes: the first
// teaches the cost (its refinement); with an unbounded budget the second is shown at full
// resolution at once, with a zero budget never.
TEST(PaintLoop, ASmallChangeIsShownAtFullResolutionAtOnceWhenItFitsTheBudget) {
  constexpr int w = 480, h = 270;
  const std::string dir = tempDir();
  const std::vector<SyntheticStroke> reference = referencePaintStrokes(w, h);
  ASSERT_GE(reference.size(), 2u);
  const std::string path =
      writeStrokeJournal(dir + "/two_strokes.cbj", {reference[0], reference[1]}, w, h);
  std::string error;
  std::unique_ptr<Display> display = test::openTestDisplay(w, h, &error);
  ASSERT_TRUE(display) << error;
  for (const double budget_ms : {1e9, 0.0}) {
    VolumeRenderer renderer;
    ASSERT_TRUE(renderer.init(&error)) << error;
    PaintSession session({w, h, 64}, BrushConfig{}, MappingConfig{});
    session.setQuietMapping(true);
    ReplayOptions replay_options;
    replay_options.realtime = false;
    replay_options.batch = 4;
    ReplayPenSource pen(path, replay_options);
    PaintLoopOptions options;
    options.max_frames = 3000;
    options.lift_budget_ms = budget_ms;
    options.config_dir = dir + "/config";
    options.state_dir = dir + "/state";
    std::vector<float> lit_scales;
    std::vector<bool> lit_is_refined;
    options.on_frame = [&](const PaintFrameInfo& info) {
      if (!info.first_lit_after_lift) return;
      lit_scales.push_back(info.render_scale);
      lit_is_refined.push_back(info.refined_after_lift);
    };
    PaintLoop loop(*display, renderer, session.volume(), Light{}, options);
    loop.attachPen(&pen, &session);
    PaintLoopSummary summary;
    ASSERT_TRUE(loop.run(nullptr, &summary, &error)) << error;
    ASSERT_EQ(lit_scales.size(), 2u) << "budget " << budget_ms;
    EXPECT_LT(lit_scales[0], 1.0f) << "no full-resolution cost is known before the first lift";
    EXPECT_FALSE(lit_is_refined[0]);
    EXPECT_EQ(summary.pen_up_to_refined_ms.size(), 2u) << "every lift ends at full resolution";
    if (budget_ms > 0.0) {
      EXPECT_EQ(lit_scales[1], 1.0f) << "the second change fits an unbounded budget";
      EXPECT_TRUE(lit_is_refined[1]);
    } else {
      EXPECT_LT(lit_scales[1], 1.0f) << "nothing fits a zero budget";
      EXPECT_FALSE(lit_is_refined[1]);
    }
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cb
