// The painter's keys and heads-up overlay through PaintLoop on the surfaceless display (EGL on
// llvmpipe), keys injected into the display's event queue:
//   S  the statistics bars are on screen with the heights RenderStats' histogram gives;
//   C  after a replayed stroke, ring pixels lie on the mapping's circles mapped to the screen;
//   B/M  journalled as UI records; replaying the journal gives the same volume checksum, and a
//        different one from the same stroke without the keys.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "app/render/image_io.h"
#include "app/scene/drawable_region.h"
#include "app/session/paint_session.h"
#include "app/session/session_replay.h"
#include "app/session/synthetic_session.h"
#include "app/shell/painter/hud_items.h"
#include "app/shell/painter/paint_loop.h"
#include "app/volume/scene_generators.h"
#include "drivers/replay/replay_pen_source.h"
#include "tests/support/test_display.h"

namespace cb {
namespace {

constexpr int kW = 640, kH = 360, kGrid = 64;

std::string tempDir(const char* name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   (std::string("cb_paint_hud_") + name + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir.string();
}

std::unique_ptr<Display> openSurfaceless() {
  std::string error;
  std::unique_ptr<Display> display = test::openTestDisplay(kW, kH, &error);
  EXPECT_TRUE(display) << error;
  return display;
}

void pressKey(Display& display, char key) {
  display.injectEvent(DisplayEvent::key(uint32_t(key)));
}

// A journal of one reference stroke (the gentle curve) at this screen size.
std::string writeStrokeJournal(const std::string& dir) {
  const std::string path = dir + "/stroke.cbj";
  PaintSession recorder({kW, kH, kGrid}, BrushConfig{}, MappingConfig{});
  recorder.setQuietMapping(true);
  JournalWriter journal;
  EXPECT_TRUE(journal.open(path)) << journal.error();
  recorder.recordTo(&journal, 0);
  const PenDeviceInfo tablet = syntheticTablet(kW, kH);
  recorder.setDevice(tablet, 0);
  for (const PenSample& s :
       syntheticPenSamples(gentleCurve(kW, kH), tablet, kW, kH, 200.0, 1'000'000'000))
    recorder.feed(s);
  EXPECT_EQ(recorder.strokesMapped(), 1u);
  return path;
}

bool colourIs(const ImageRgba8& image, int x, int y, glm::vec4 colour) {
  if (x < 0 || y < 0 || x >= image.width || y >= image.height) return false;
  const size_t i = (size_t(y) * size_t(image.width) + size_t(x)) * 4;
  for (int c = 0; c < 3; ++c)
    if (std::abs(int(image.pixels[i + size_t(c)]) - int(std::lround(colour[c] * 255.0f))) > 1)
      return false;
  return true;
}

TEST(PaintHud, StatsBarsFollowTheHistogram) {
  std::unique_ptr<Display> display = openSurfaceless();
  ASSERT_TRUE(display);
  std::string error;
  VolumeRenderer renderer;
  ASSERT_TRUE(renderer.init(&error)) << error;
  const Volume volume = makeBundledCumulus(glm::ivec3(kGrid));
  PaintLoopOptions options;
  options.orbit_degrees_per_second = 0.0f;  // still: one full-resolution frame
  options.max_frames = 1;
  ImageRgba8 frame;
  RenderStats stats;
  options.on_frame = [&](const PaintFrameInfo&) {
    frame = readFramebufferRgba8(display->framebuffer(), kW, kH);
    stats = renderer.lastStats();
  };
  pressKey(*display, 's');
  PaintLoop loop(*display, renderer, volume, Light{}, options);
  PaintLoopSummary summary;
  ASSERT_TRUE(loop.run(nullptr, &summary, &error)) << error;
  ASSERT_EQ(summary.frames, 1);
  ASSERT_TRUE(stats.has_samples) << "S must turn on ray-sample statistics";
  ASSERT_GT(stats.histogram.size(), 2u);

  const StatsPanelLayout layout = statsPanelLayout(kW, kH);
  const std::vector<int> expected = statsBarHeights(stats.histogram, layout.max_height);
  int distinct_heights = 0, last = -1;
  for (size_t bin = 0; bin < expected.size(); ++bin) {
    const int x = layout.left + int(bin) * layout.bar_pitch + layout.bar_width / 2;
    int height = 0;  // bar-coloured pixels from the baseline upwards
    while (height <= layout.max_height + 2 &&
           colourIs(frame, x, layout.baseline_y - 1 - height, kHudBarColour))
      ++height;
    EXPECT_EQ(height, expected[bin]) << "bin " << bin << " (" << stats.histogram[bin] << " pixels)";
    // The gap between bars is not bar-coloured.
    EXPECT_FALSE(colourIs(frame, layout.left + int(bin) * layout.bar_pitch + layout.bar_width,
                          layout.baseline_y - 1, kHudBarColour));
    if (expected[bin] != last) ++distinct_heights;
    last = expected[bin];
  }
  EXPECT_GE(distinct_heights, 3) << "a histogram with some shape, so the check means something";
  if (const char* keep = std::getenv("CB_PAINT_HUD_KEEP_FRAMES"))
    writePng(std::string(keep) + "/hud_stats.png", frame);
  // Without S there are no bars.
  PaintLoopOptions plain = options;
  ImageRgba8 plain_frame;
  plain.on_frame = [&](const PaintFrameInfo&) {
    plain_frame = readFramebufferRgba8(display->framebuffer(), kW, kH);
  };
  PaintLoop plain_loop(*display, renderer, volume, Light{}, plain);
  ASSERT_TRUE(plain_loop.run(nullptr, &summary, &error)) << error;
  long bar_pixels = 0;
  for (int y = layout.baseline_y - layout.max_height; y < layout.baseline_y; ++y)
    for (int x = layout.left; x < layout.left + int(expected.size()) * layout.bar_pitch; ++x)
      bar_pixels += colourIs(plain_frame, x, y, kHudBarColour);
  EXPECT_LT(bar_pixels, 20);
  std::printf("histogram of %zu bins, total %llu samples, mean %.1f, max %u\n",
              stats.histogram.size(), static_cast<unsigned long long>(stats.samples_total),
              stats.samples_mean, stats.samples_max);
}

struct ReplayRun {
  std::unique_ptr<PaintSession> session;
  ImageRgba8 before_lift, after_lift;  // the last frame of the stroke, the lit frames
  bool have_before = false, have_after = false;
};

// Plays `journal` through PaintLoop, pressing `keys` before the first frame, in a sky of
// `sky_span` home boxes; records to `record_to` when given.
ReplayRun runReplay(const std::string& journal, const std::string& dir, const std::string& keys,
                    JournalWriter* record_to, int sky_span = kDefaultSkySpan) {
  ReplayRun run;
  std::unique_ptr<Display> display = openSurfaceless();
  if (!display) return run;
  std::string error;
  VolumeRenderer renderer;
  EXPECT_TRUE(renderer.init(&error)) << error;
  PaintSessionSettings settings{kW, kH, kGrid};
  settings.sky_span = sky_span;
  if (sky_span == kLegacySkySpan) settings.sky_max_span = kLegacySkySpan;  // the old box
  run.session = std::make_unique<PaintSession>(settings, BrushConfig{}, MappingConfig{});
  run.session->setQuietMapping(true);
  if (record_to) run.session->recordTo(record_to, 0);
  ReplayOptions replay_options;
  replay_options.realtime = false;
  replay_options.batch = 16;
  ReplayPenSource pen(journal, replay_options);
  PaintLoopOptions options;
  options.max_frames = 2000;
  options.config_dir = dir + "/config";
  options.state_dir = dir + "/state";
  options.on_frame = [&](const PaintFrameInfo& info) {
    if (!info.painting_view) return;
    if (info.in_stroke && !info.first_lit_after_lift && !run.have_after) {
      run.before_lift = readFramebufferRgba8(display->framebuffer(), kW, kH);
      run.have_before = true;
    }
    if (info.first_lit_after_lift || info.refined_after_lift) {
      run.after_lift = readFramebufferRgba8(display->framebuffer(), kW, kH);
      run.have_after = true;
    }
  };
  for (char key : keys) pressKey(*display, key);
  PaintLoop loop(*display, renderer, run.session->volume(), Light{}, options);
  loop.attachPen(&pen, run.session.get());
  PaintLoopSummary summary;
  EXPECT_TRUE(loop.run(nullptr, &summary, &error)) << error;
  EXPECT_EQ(summary.quit_reason, "replay finished");
  EXPECT_EQ(summary.strokes_mapped, 1);
  return run;
}

TEST(PaintHud, CircleRingsLieOnTheMappingCircles) {
  const std::string dir = tempDir("circles");
  const std::string journal = writeStrokeJournal(dir);
  // In the one-box sky, whose drawable region has sides on the screen to check the outline on
  // (the default sky's canvas reaches past every edge of the default view).
  ReplayRun run = runReplay(journal, dir, "c", nullptr, kLegacySkySpan);
  ASSERT_TRUE(run.session && run.have_before && run.have_after);
  const std::vector<Circle>& circles = run.session->lastCircles();
  ASSERT_GE(circles.size(), 3u);
  const float scale = float(kW) / float(run.session->footprintWidth());
  long probes = 0, on_ring_after = 0, on_ring_before = 0;
  for (const Circle& circle : circles) {
    const glm::vec2 centre = footprintToScreen(circle.centre, run.session->footprintWidth(),
                                               run.session->footprintHeight(), kW, kH);
    const float radius = float(circle.radius) * scale;
    for (int k = 0; k < 8; ++k) {
      const float angle = float(k) * 0.785398163f;
      const glm::vec2 p = centre + radius * glm::vec2(std::cos(angle), std::sin(angle));
      const int x = int(std::floor(p.x)), y = int(std::floor(p.y));
      if (x < 0 || y < 0 || x >= kW || y >= kH) continue;
      ++probes;
      on_ring_after += colourIs(run.after_lift, x, y, kHudRingColour);
      on_ring_before += colourIs(run.before_lift, x, y, kHudRingColour);
    }
  }
  ASSERT_GT(probes, 20);
  EXPECT_GE(double(on_ring_after), 0.9 * double(probes)) << "ring pixels on the circles";
  EXPECT_EQ(on_ring_before, 0) << "no ring colour while the stroke was drawn";
  std::printf("%zu circles, %ld/%ld probes on a ring\n", circles.size(), on_ring_after, probes);
  // While the pen was in range the drawable region was outlined: each side's midpoint inside
  // the screen is tinted against the sky 8 px away across the side (ink may cover one or two).
  const DrawableRegion region(run.session->camera(), run.session->canvas(),
                              run.session->volume().worldMin(), run.session->volume().worldMax(),
                              kW, kH);
  const std::vector<glm::vec2> outline = region.outline();
  ASSERT_GE(outline.size(), 4u);
  size_t tinted = 0, eligible = 0;
  for (size_t i = 0; i < outline.size(); ++i) {
    const glm::vec2 a = outline[i], b = outline[(i + 1) % outline.size()];
    const glm::vec2 mid = 0.5f * (a + b), across = glm::normalize(glm::vec2(a.y - b.y, b.x - a.x));
    const glm::vec2 off = mid + 8.0f * across;
    const auto on_screen = [](glm::vec2 p) {
      return p.x >= 2 && p.y >= 2 && p.x < kW - 2 && p.y < kH - 2;
    };
    if (!on_screen(mid) || !on_screen(off)) continue;  // a side along the screen's edge
    ++eligible;
    const auto at = [&](glm::vec2 p, int c) {
      return int(run.before_lift.pixels[(size_t(p.y) * kW + size_t(p.x)) * 4 + size_t(c)]);
    };
    int difference = 0;
    for (int c = 0; c < 3; ++c)
      difference = std::max(difference, std::abs(at(mid, c) - at(off, c)));
    tinted += difference >= 8;
  }
  ASSERT_GE(eligible, 2u);
  EXPECT_GE(tinted + 1, eligible) << tinted << " of " << eligible << " sides tinted";
  std::printf("drawable-region outline: %zu of %zu sides tinted\n", tinted, eligible);
  if (const char* keep = std::getenv("CB_PAINT_HUD_KEEP_FRAMES")) {  // for looking at them
    writePng(std::string(keep) + "/hud_rings.png", run.after_lift);
    writePng(std::string(keep) + "/hud_during_stroke.png", run.before_lift);
  }
  std::filesystem::remove_all(dir);
}

TEST(PaintHud, BrushAndMappingKeysAreJournalledAndReplayed) {
  const std::string dir = tempDir("keys");
  const std::string stroke = writeStrokeJournal(dir);
  const std::string recorded = dir + "/keys.cbj";
  uint64_t painted_sum = 0;
  BrushKind initial_brush{};
  {
    JournalWriter journal;
    ASSERT_TRUE(journal.open(recorded)) << journal.error();
    ReplayRun run = runReplay(stroke, dir, "bn", &journal);
    ASSERT_TRUE(run.session);
    initial_brush = PaintSession({kW, kH, kGrid}, BrushConfig{}, MappingConfig{}).selectedBrush();
    EXPECT_NE(run.session->selectedBrush(), initial_brush);
    EXPECT_EQ(run.session->mappingMethod(), MappingMethod::kRayMarching);
    painted_sum = volumeChecksum(run.session->volume());
  }
  const JournalReadResult read = readJournal(recorded);
  ASSERT_TRUE(read.error.empty()) << read.error;
  std::vector<std::string> ui;
  for (const JournalRecord& record : read.records)
    if (record.type == JournalRecordType::kUi) ui.emplace_back(record.text());
  bool brush_key = false, method_key = false;
  // recordTo journals the settings in force first (brush, then method, ...); the key presses
  // come after them.
  size_t start = 0;
  while (start < ui.size() && ui[start].rfind("method=", 0) != 0) ++start;
  for (size_t i = start + 1; i < ui.size(); ++i) {
    brush_key |= ui[i].rfind("brush=", 0) == 0 &&
                 ui[i] != std::string("brush=") + brushKindName(initial_brush);
    method_key |= ui[i] == "method=ray-marching";
  }
  EXPECT_TRUE(brush_key && method_key) << ui.size() << " UI records";

  const SessionReplay replay = replaySession(read, BrushConfig{}, MappingConfig{});
  ASSERT_TRUE(replay.session);
  EXPECT_TRUE(replay.complete());
  EXPECT_EQ(replay.strokes_mapped, 1u);
  EXPECT_EQ(volumeChecksum(replay.session->volume()), painted_sum);
  // The keys changed the result: the same stroke without them gives another volume.
  const SessionReplay plain = replaySession(readJournal(stroke), BrushConfig{}, MappingConfig{});
  ASSERT_TRUE(plain.session);
  EXPECT_NE(volumeChecksum(plain.session->volume()), painted_sum);
  std::filesystem::remove_all(dir);
}

// The canvas-region hint: a convex outline whose inside is where a pixel ray meets the canvas
// slab inside the volume's box, and whose far outside misses it.
TEST(PaintHud, CanvasRegionOutlineBoundsWhereRaysMeetTheSlabInTheVolume) {
  const Camera camera = Camera::reference();
  const Canvas canvas;
  const glm::vec3 lo(-1.0f), hi(1.0f);
  const std::vector<glm::vec2> outline = canvasRegionOutline(camera, canvas, lo, hi, kW, kH);
  ASSERT_GE(outline.size(), 4u);
  ASSERT_LE(outline.size(), 8u);
  const auto inside = [&](glm::vec2 p) {  // convex, consistently wound
    float sign = 0.0f;
    for (size_t i = 0; i < outline.size(); ++i) {
      const glm::vec2 a = outline[i], b = outline[(i + 1) % outline.size()];
      const float c = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
      if (c * sign < 0.0f) return false;
      if (c != 0.0f) sign = c;
    }
    return true;
  };
  const auto ray_meets_slab = [&](float px, float py) {
    glm::vec3 origin, dir;
    camera.pixelRay(px, py, kW, kH, &origin, &dir);
    float t = 0.0f;
    if (!canvas.intersectMidPlane(origin, dir, &t)) return false;
    const glm::vec3 p = origin + t * dir;
    return p.x >= lo.x && p.x <= hi.x && p.z >= lo.z && p.z <= hi.z;
  };
  long agree = 0, total = 0, hits = 0;
  for (int y = 4; y < kH; y += 16)
    for (int x = 4; x < kW; x += 16) {
      const bool meets = ray_meets_slab(float(x) + 0.5f, float(y) + 0.5f);
      hits += meets;
      // Every ray meeting the mid-plane inside the box is inside the outline.
      if (meets) {
        ++total;
        agree += inside({float(x) + 0.5f, float(y) + 0.5f});
      }
    }
  ASSERT_GT(hits, 50);
  EXPECT_EQ(agree, total);
  // A slab above the box has no region.
  Canvas above;
  above.altitude = 3.0f;
  EXPECT_TRUE(canvasRegionOutline(camera, above, lo, hi, kW, kH).empty());
}

}  // namespace
}  // namespace cb

namespace cb {
namespace {

// The Vacuum's three axis-plane grids (§3.5.1): every line lies on one of the planes through
// the sphere's centre, spans the box, and a plane the centre is outside of is left out.
TEST(PaintHud, VacuumAxisPlaneGridsLieOnThePlanesThroughTheCentre) {
  const glm::vec3 lo(-1.0f), hi(1.0f), centre(0.25f, -0.5f, 0.75f);
  std::vector<glm::vec3> ends;
  const auto to_screen = [&](glm::vec3 p) {
    ends.push_back(p);
    return glm::vec2(p.x, p.z);
  };
  std::vector<HudItem> items;
  appendAxisPlaneGrids(centre, lo, hi, 4, to_screen, &items);
  ASSERT_EQ(items.size(), 3u * 2u * 5u);
  ASSERT_EQ(ends.size(), 2 * items.size());
  int on_plane[3] = {0, 0, 0};
  for (size_t i = 0; i < ends.size(); i += 2) {
    const glm::vec3 a = ends[i], b = ends[i + 1];
    int planes = 0;
    for (int axis = 0; axis < 3; ++axis)
      if (a[axis] == centre[axis] && b[axis] == centre[axis]) ++on_plane[axis], ++planes;
    EXPECT_GE(planes, 1) << "segment " << i / 2 << " is on no plane through the centre";
    EXPECT_NEAR(glm::length(b - a), 2.0f, 1e-6f) << "spans the box";
  }
  for (int axis = 0; axis < 3; ++axis) EXPECT_GE(on_plane[axis], 10) << axis;
  items.clear();
  appendAxisPlaneGrids(glm::vec3(0.0f, 3.0f, 0.0f), lo, hi, 4, to_screen, &items);
  EXPECT_EQ(items.size(), 2u * 2u * 5u) << "the y plane lies outside the box";
}

}  // namespace
}  // namespace cb
