// The sky grows with what is painted ("growing with what is painted"), with the
// product's defaults — the painter's 1280×720 screen and grid 256, the default sky (4 home boxes
// across, growing up to 8), config/brush.toml and config/mapping.toml, the default paint camera
// panned along the canvas as the camera mode pans it, the real brushes through PaintSession:
//   - a stroke drawn across the default sky's edge grows the sky first and lands whole: the same
//     voxels, in world space, as in a sky made 8 boxes wide from the start, and it renders as
//     that one does (the renderer follows the new extent); a sky that may not grow (a journal
//     recorded before the sky grew) clips it as before;
//   - undo and redo go on across the growth;
//   - a journal with growth replays byte-identically on 1, 2 and 8 threads;
//   - the light of a cloud is the same before and after the sky grows around it;
//   - a picture or model placed where the view looks past the sky's edge (the real tools, the
//     bundled study picture and a generated torus) grows the sky first and lands whole, undo and
//     redo go on across it, its journal replays byte-identically on 1 and 2 threads, and a
//     journal of specification 1.4 (no `placements_grow_sky`) still clips it, to the checksum
//     it replayed to before placements grew the sky.
//   - the renderer follows a growth (shifts what it holds) and then holds and draws what a fresh
//     sync of the grown sky holds and draws.
#include <chrono>
#include <cstdio>
#include <deque>
#include <filesystem>

#include <unistd.h>

#include <gtest/gtest.h>

#include "app/core/config_paths.h"
#include "app/core/parallel_for.h"
#include "app/render/image_io.h"
#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"
#include "app/scene/paint_camera.h"
#include "app/session/paint_session.h"
#include "app/session/session_replay.h"
#include "app/session/synthetic_session.h"
#include "app/tools/procedural_mesh.h"
#include "app/volume/scene_generators.h"
#include "tests/support/session_painter.h"
#include "tests/unit/mapping/rendered_opacity.h"
#include "tests/unit/render/gl_test_context.h"

namespace cb {
namespace {

constexpr int kW = 1280, kH = 720;  // PaintSessionSettings' screen
constexpr int kGrid = 256;          // the painter's grid (cloudbrush paint --grid)

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// The settings `cloudbrush paint` makes a session with (command_paint.cpp).
PaintSessionSettings productSettings() {
  PaintSessionSettings settings{kW, kH, kGrid};
  const BrushConfig brush = loadDefaultBrushConfig();
  settings.auto_end_still_ms = brush.stroke.auto_end_still_ms;
  settings.auto_end_light_ms = brush.stroke.auto_end_light_ms;
  return settings;
}

// The default paint view panned by `shift` along the canvas (the camera mode's pan).
Camera pannedPaintCamera(glm::vec3 shift) {
  return defaultPaintCamera(Canvas{}, glm::vec3(-1.0f) + shift, glm::vec3(1.0f) + shift,
                            float(kW) / float(kH));
}

// The view centred on the default sky's +x edge (x = 4): the gentle curve crosses it.
const Camera kEdgeView = pannedPaintCamera(glm::vec3(float(kDefaultSkySpan), 0.0f, 0.0f));

// The painter with the product's brushes and mapping.
struct Painter : test::SessionPainter {
  explicit Painter(const PaintSessionSettings& settings = productSettings())
      : SessionPainter(settings, loadDefaultBrushConfig(),
                       loadMappingConfig(configFile("mapping.toml"))) {}
};

// `v` (a sky of extent `from`) as it sits in the wider sky `to`: a copy grown around it.
Volume grownCopy(const Volume& v, const SkyExtent& from, const SkyExtent& to) {
  return to.span == from.span ? v : growSky(Volume(v), from, to);
}

// Voxels that differ between two volumes of the same grid (in either's allocated bricks).
long long differingVoxels(const Volume& a, const Volume& b) {
  EXPECT_EQ(a.dims(), b.dims());
  long long n = 0;
  for (const Volume* v : {&a, &b})
    for (const glm::ivec3& brick : v->allocatedBrickList()) {
      const VoxelBox box = v->brickBox(brick);
      for (int z = box.lo.z; z < box.hi.z; ++z)
        for (int y = box.lo.y; y < box.hi.y; ++y)
          for (int x = box.lo.x; x < box.hi.x; ++x)
            n += a.at(x, y, z) != b.at(x, y, z) && (v == &a || !a.brick(brick));
    }
  return n;
}

double densitySum(const Volume& v, long long* nonzero = nullptr) {
  double sum = 0.0;
  long long n = 0;
  for (const glm::ivec3& brick : v.allocatedBrickList()) {
    const float* d = v.brick(brick);
    for (int i = 0; i < Volume::kBrickVoxels; ++i) {
      sum += d[i];
      n += d[i] != 0.0f;
    }
  }
  if (nonzero) *nonzero = n;
  return sum;
}

TEST(SkyGrowth, TheSessionRecordSaysHowFarTheSkyMayGrowAndOldRecordsDoNotGrow) {
  const PaintSessionSettings defaults = productSettings();
  EXPECT_EQ(defaults.sky_span, kDefaultSkySpan);
  EXPECT_EQ(defaults.sky_max_span, kMaxSkySpan);
  PaintSessionSettings parsed;
  std::string error;
  ASSERT_TRUE(parseSessionSettings(formatSessionSettings(defaults), &parsed, &error)) << error;
  EXPECT_EQ(parsed.sky_span, kDefaultSkySpan);
  EXPECT_EQ(parsed.sky_max_span, kMaxSkySpan);
  // A record of a fixed sky (before the sky grew), and of the one-box sky.
  ASSERT_TRUE(parseSessionSettings("grid = 256\nsky_span = 4\nformat = 2\n", &parsed, &error));
  EXPECT_EQ(parsed.sky_max_span, 4);
  ASSERT_TRUE(parseSessionSettings("grid = 256\nformat = 2\n", &parsed, &error));
  EXPECT_EQ(parsed.sky_span, kLegacySkySpan);
  EXPECT_EQ(parsed.sky_max_span, kLegacySkySpan);
  EXPECT_FALSE(
      parseSessionSettings("grid = 256\nsky_span = 4\nsky_max_span = 3\n", &parsed, &error));
  EXPECT_NE(error.find("sky_max_span"), std::string::npos) << error;
  EXPECT_FALSE(parseSessionSettings("grid = 256\nsky_max_span = 9\n", &parsed, &error));
  // Placements grow the sky since specification 1.5; a record without the key (1.4 and older)
  // does not let them, and a sky that may not grow does not write it (the attract journal).
  EXPECT_TRUE(defaults.placementsGrowSky());
  ASSERT_TRUE(parseSessionSettings(formatSessionSettings(defaults), &parsed, &error)) << error;
  EXPECT_TRUE(parsed.placementsGrowSky());
  ASSERT_TRUE(parseSessionSettings("grid = 256\nsky_span = 4\nsky_max_span = 8\nformat = 2\n",
                                   &parsed, &error));
  EXPECT_FALSE(parsed.placementsGrowSky());
  PaintSessionSettings fixed = defaults;
  fixed.sky_max_span = fixed.sky_span;
  EXPECT_EQ(formatSessionSettings(fixed).find("placements_grow_sky"), std::string::npos);
  EXPECT_FALSE(parseSessionSettings("grid = 256\nsky_max_span = 8\nplacements_grow_sky = yes\n",
                                    &parsed, &error));
  EXPECT_EQ(error, "session line 3: placements_grow_sky: expected true or false, got 'yes'");
}

class SkyGrowthGl : public ::testing::Test {
 protected:
  void SetUp() override {
    CB_REQUIRE_GL();
    std::string err;
    ASSERT_TRUE(renderer.init(&err)) << err;
    ASSERT_TRUE(target.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  }
  VolumeRenderer renderer;
  RenderTarget target;
};

TEST_F(SkyGrowthGl, AStrokePastTheDefaultEdgeGrowsTheSkyLandsWholeAndRenders) {
  const SyntheticStroke curve = gentleCurve(kW, kH);
  // Growing (the default), a sky 8 boxes wide from the start, and one fixed at the default.
  Painter growing;
  PaintSessionSettings wide_settings = productSettings();
  wide_settings.sky_span = wide_settings.sky_max_span = kMaxSkySpan;
  Painter wide(wide_settings);
  PaintSessionSettings fixed_settings = productSettings();
  fixed_settings.sky_max_span = fixed_settings.sky_span;
  Painter fixed(fixed_settings);
  ASSERT_EQ(growing.session.reachableSky().span, kMaxSkySpan);
  ASSERT_EQ(fixed.session.reachableSky().span, kDefaultSkySpan);

  // A first stroke in the home box: the sky does not grow; the renderer syncs it.
  growing.stroke(curve);
  ASSERT_EQ(growing.session.strokesMapped(), 1u);
  EXPECT_EQ(growing.session.sky().span, kDefaultSkySpan);
  EXPECT_EQ(growing.session.skyGrowths(), 0u);
  renderer.sync(growing.session.volume(), Light{});
  const uint64_t before_id = growing.session.volume().instanceId();
  for (Painter* p : {&wide, &fixed}) p->stroke(curve);

  for (Painter* p : {&growing, &wide, &fixed}) {
    p->apply(ui::SetCamera{kEdgeView});
    p->stroke(curve);
    ASSERT_EQ(p->session.strokesMapped(), 2u);
  }
  const PaintSession& g = growing.session;
  EXPECT_GT(g.sky().span, kDefaultSkySpan) << "the stroke across the edge did not grow the sky";
  EXPECT_LE(g.sky().span, kMaxSkySpan);
  EXPECT_EQ(g.skyGrowths(), 1u);
  EXPECT_EQ(g.lastGrowthStroke(), 1u);  // stroke indices count from 0
  EXPECT_EQ(g.volume().dims(), g.sky().dims());
  EXPECT_NE(g.volume().instanceId(), before_id);
  EXPECT_EQ(fixed.session.sky().span, kDefaultSkySpan);

  // Whole: the grown sky holds, voxel for voxel, what the wide sky holds; the fixed sky lost
  // the part past its edge.
  const SkyExtent wide_sky{kGrid, kMaxSkySpan};
  const Volume grown_in_wide = grownCopy(g.volume(), g.sky(), wide_sky);
  const long long differing = differingVoxels(grown_in_wide, wide.session.volume());
  long long voxels = 0;
  const double sum_grown = densitySum(g.volume(), &voxels),
               sum_wide = densitySum(wide.session.volume()),
               sum_fixed = densitySum(fixed.session.volume());
  std::printf(
      "stroke across x = %d: the sky grew to span %d (%dx%dx%d); density %.1f in %lld voxels, in "
      "a sky 8 wide %.1f (%lld voxels differ), in the fixed sky %.1f\n",
      kDefaultSkySpan, g.sky().span, g.sky().dims().x, g.sky().dims().y, g.sky().dims().z,
      sum_grown, voxels, sum_wide, differing, sum_fixed);
  // The mapping turns world positions into voxels from the sky's corner, so a sky whose corner
  // lies elsewhere may round an edge-scatter sample into the neighbouring voxel: one voxel of
  // 18,410 here. Nothing is clipped: the densities agree to 1e-4.
  EXPECT_LE(differing, voxels / 10000);
  EXPECT_NEAR(sum_grown, sum_wide, 1e-4 * sum_wide);
  EXPECT_LT(sum_fixed, 0.9 * sum_grown) << "the stroke did not reach past the default edge";

  // It renders: the renderer that showed the sky before it grew follows the growth and draws what
  // a fresh renderer draws of the sky made wide from the start.
  const auto t0 = std::chrono::steady_clock::now();
  const SyncStats synced = renderer.sync(g.volume(), Light{});
  const double sync_ms = msSince(t0);
  EXPECT_TRUE(synced.followed_growth);
  const std::vector<float> seen = test::renderedOpacity(renderer, target, g.volume(), kEdgeView);
  VolumeRenderer other;
  std::string err;
  ASSERT_TRUE(other.init(&err)) << err;
  const std::vector<float> seen_wide =
      test::renderedOpacity(other, target, wide.session.volume(), kEdgeView);
  const std::vector<float> seen_fixed =
      test::renderedOpacity(other, target, fixed.session.volume(), kEdgeView);
  long long cloud = 0, cloud_fixed = 0, off = 0;
  for (size_t i = 0; i < seen.size(); ++i) {
    cloud += seen[i] > 0.5f;
    cloud_fixed += seen_fixed[i] > 0.5f;
    off += std::abs(seen[i] - seen_wide[i]) > 2.5f / 255.0f;
  }
  std::printf(
      "sync of the grown sky (followed: %d): %.1f ms (occupancy %.1f, light %.1f, pack %.1f, "
      "upload %.1f); "
      "%lld cloud pixels (fixed sky: %lld), %lld differ from the wide sky's by > 2/255\n",
      int(synced.followed_growth), sync_ms, synced.occupancy_ms, synced.light_ms, synced.pack_ms,
      synced.upload_ms, cloud, cloud_fixed, off);
  EXPECT_GT(cloud, 20000);
  EXPECT_LT(cloud_fixed, cloud * 9 / 10);
  EXPECT_LE(off, kW * kH / 10000);
}

TEST(SkyGrowth, UndoAndRedoGoOnAcrossTheGrowth) {
  const SyntheticStroke curve = gentleCurve(kW, kH);
  Painter p;
  p.stroke(curve);  // in the home box
  const SkyExtent home_sky = p.session.sky();
  const Volume after_first = p.session.volume();
  p.apply(ui::SetCamera{kEdgeView});
  p.stroke(curve);  // grows the sky
  const SkyExtent grown_sky = p.session.sky();
  ASSERT_GT(grown_sky.span, home_sky.span);
  const uint64_t after_second = volumeChecksum(p.session.volume());
  const Volume first_in_grown = grownCopy(after_first, home_sky, grown_sky);

  p.apply(ui::Undo{});  // the stroke that grew the sky: gone, the sky stays grown
  EXPECT_EQ(p.session.sky().span, grown_sky.span);
  EXPECT_EQ(volumeChecksum(p.session.volume()), volumeChecksum(first_in_grown));
  p.apply(ui::Undo{});  // the camera
  p.apply(ui::Undo{});  // the first stroke
  EXPECT_FALSE(p.session.volume().hasDensity());
  EXPECT_EQ(p.session.volume().allocatedBricks(), 0u);
  p.apply(ui::Redo{});
  EXPECT_EQ(volumeChecksum(p.session.volume()), volumeChecksum(first_in_grown));
  p.apply(ui::Redo{});
  p.apply(ui::Redo{});
  EXPECT_EQ(volumeChecksum(p.session.volume()), after_second);
  EXPECT_EQ(p.session.camera().eye, kEdgeView.eye);
}

TEST(SkyGrowth, AJournalWithGrowthReplaysByteIdenticallyOnOneTwoAndEightThreads) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("cb_sky_growth_" + std::to_string(::getpid()) + ".cbj"))
                               .string();
  const std::vector<SyntheticStroke> strokes = referencePaintStrokes(kW, kH);
  uint64_t sum = 0;
  SkyExtent sky;
  {
    Painter p;
    JournalWriter journal;
    ASSERT_TRUE(journal.open(path)) << journal.error();
    p.session.recordTo(&journal, 0);
    p.stroke(strokes[0]);
    p.apply(ui::SetCamera{kEdgeView});
    p.stroke(strokes[1]);  // grows the sky
    p.apply(ui::Undo{});
    p.apply(ui::Redo{});
    p.apply(ui::SetCamera{pannedPaintCamera(glm::vec3(-6.0f, 0.0f, 5.0f))});
    p.stroke(strokes[0]);  // grows it again, the other way
    journal.close();
    sum = volumeChecksum(p.session.volume());
    sky = p.session.sky();
    EXPECT_EQ(p.session.skyGrowths(), 2u);
  }
  const int threads = workerThreads();
  for (int n : {1, 2, 8}) {
    setWorkerThreads(n);
    const SessionReplay replay = replaySession(readJournal(path), BrushConfig{}, MappingConfig{});
    ASSERT_TRUE(replay.session);
    EXPECT_TRUE(replay.complete())
        << replay.journal_error << (replay.problems.empty() ? "" : replay.problems[0]);
    EXPECT_TRUE(replay.recorded_settings);
    EXPECT_EQ(replay.session->sky().span, sky.span) << n << " threads";
    EXPECT_EQ(replay.session->skyGrowths(), 2u) << n << " threads";
    EXPECT_EQ(volumeChecksum(replay.session->volume()), sum) << n << " threads";
  }
  setWorkerThreads(threads);
  std::filesystem::remove(path);
}

// Memory follows the painting however wide the sky has grown: the widest sky, empty, holds
// ≤ 50 MB (volume bricks + the renderer's GPU copies + its light volume, counted in bytes).
TEST_F(SkyGrowthGl, AnEmptySkyGrownToItsWidestStaysUnderFiftyMegabytes) {
  const SkyExtent widest{kGrid, widestSkySpan(kGrid, kDefaultSkySpan, kMaxSkySpan)};
  ASSERT_EQ(widest.dims(), glm::ivec3(2048, 256, 2048));
  std::deque<Volume> volumes;
  Volume& sky = volumes.emplace_back(
      growSky(makeSkyVolume({kGrid, kDefaultSkySpan}), {kGrid, kDefaultSkySpan}, widest));
  renderer.sync(sky, Light{});
  const RendererGpuMemory gpu = renderer.gpuMemory();
  const size_t bytes =
      sky.memoryBytes() + renderer.memoryBytes() + renderer.lightVolume().memoryBytes();
  std::printf(
      "empty %dx%dx%d sky: %.1f MB (volume %.1f, GPU %.1f of which occupancy %.1f, "
      "indirection %.1f, pool %.1f, frame targets %.1f; light %.1f)\n",
      widest.dims().x, widest.dims().y, widest.dims().z, bytes / 1e6, sky.memoryBytes() / 1e6,
      renderer.memoryBytes() / 1e6, gpu.occupancy / 1e6, gpu.indirection / 1e6, gpu.pool / 1e6,
      gpu.frame_targets / 1e6, renderer.lightVolume().memoryBytes() / 1e6);
  EXPECT_LE(bytes, size_t(50'000'000));
}

TEST_F(SkyGrowthGl, TheLightOfACloudIsTheSameAfterTheSkyGrowsAroundIt) {
  const SkyExtent from{kGrid, kDefaultSkySpan}, to{kGrid, kMaxSkySpan};  // to the widest
  std::deque<Volume> volumes;  // kept alive: the renderer knows a volume by its address
  Volume& before = volumes.emplace_back(placeInSky(makeBundledCumulus(glm::ivec3(kGrid), 1), from));
  const Light sun;  // the default sun: a direction
  const Camera view = initialPaintCamera(productSettings());
  RenderOptions options;
  renderer.sync(before, sun);
  const glm::ivec3 home = from.homeOffset();
  std::vector<float> light_before;
  for (int z = 0; z < kGrid; z += 4)
    for (int y = 0; y < kGrid; y += 4)
      for (int x = 0; x < kGrid; x += 4)
        light_before.push_back(renderer.lightVolume().at(home.x + x, y, home.z + z));
  renderer.render(view, kW, kH, target.fbo(), options);
  const ImageRgba8 image_before = target.readRgba8();

  Volume& after = volumes.emplace_back(growSky(Volume(before), from, to));
  const auto t0 = std::chrono::steady_clock::now();
  renderer.sync(after, sun);
  const double fresh_ms = msSince(t0);
  const glm::ivec3 moved = to.homeOffset();
  size_t i = 0;
  float worst_light = 0.0f;
  long long shadowed = 0;
  for (int z = 0; z < kGrid; z += 4)
    for (int y = 0; y < kGrid; y += 4)
      for (int x = 0; x < kGrid; x += 4) {
        const float was = light_before[i++];
        shadowed += was < 0.5f;
        worst_light = std::max(
            worst_light, std::abs(renderer.lightVolume().at(moved.x + x, y, moved.z + z) - was));
      }
  renderer.render(view, kW, kH, target.fbo(), options);
  const ImageRgba8 image_after = target.readRgba8();
  int worst = 0;
  long long off_by_more_than_one = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      int pixel = 0;
      for (int c = 0; c < 4; ++c)
        pixel =
            std::max(pixel, std::abs(int(image_before.at(x, y)[c]) - int(image_after.at(x, y)[c])));
      worst = std::max(worst, pixel);
      off_by_more_than_one += pixel > 1;
    }
  std::printf(
      "cumulus, sky span %d -> %d: fresh sync %.1f ms; light differs by at most %.2g (%lld of "
      "%zu sampled voxels in shadow); pixels by at most %d/255 (%lld by more than 1/255)\n",
      from.span, to.span, fresh_ms, double(worst_light), shadowed, light_before.size(), worst,
      off_by_more_than_one);
  EXPECT_GT(shadowed, 0) << "the cumulus casts no shadow on itself: the comparison is empty";
  EXPECT_LE(worst_light, 1e-6f);
  // The same world, sampled from a box that starts elsewhere: float rounding may move a sample
  // by an ulp, so a pixel here and there may round 2/255 apart (as for the far-edge cloud).
  EXPECT_LE(worst, 2);
  EXPECT_LE(off_by_more_than_one, kW * kH / 10000);
}

// ---- Placements (a picture or a model placed from the view) grow the sky as strokes do. ----

// The bundled study picture (a duck-shaped cloud, 512×384) and a generated torus, as files.
std::string duckPicture() {
  return configFile("study/images/cloud1_duck.png");
}
std::string torusModel() {
  static const std::string path = [] {
    const std::string p = (std::filesystem::temp_directory_path() /
                           ("cb_sky_growth_torus_" + std::to_string(::getpid()) + ".obj"))
                              .string();
    writeObj(p, makeDisplacedTorus(0.5f, 0.2f, 0.1f, 32, 24));
    return p;
  }();
  return path;
}

// Settings of a journal recorded before placements grew the sky (specification 1.4): the sky
// grows with strokes only.
PaintSessionSettings strokesOnlySettings() {
  PaintSessionSettings settings = productSettings();
  settings.placements_grow_sky = false;
  return settings;
}

// Non-zero voxels of `v` whose centre lies past world |x| or |z| = `edge`.
long long voxelsPast(const Volume& v, float edge) {
  long long n = 0;
  for (const glm::ivec3& brick : v.allocatedBrickList()) {
    const VoxelBox box = v.brickBox(brick);
    for (int z = box.lo.z; z < box.hi.z; ++z)
      for (int y = box.lo.y; y < box.hi.y; ++y)
        for (int x = box.lo.x; x < box.hi.x; ++x) {
          const glm::vec3 w = v.voxelToWorld(glm::vec3(x, y, z) + 0.5f);
          n += v.at(x, y, z) != 0.0f && (std::abs(w.x) > edge || std::abs(w.z) > edge);
        }
  }
  return n;
}

// The view centred a home box past the default sky's -x edge (x = -5): wholly outside it.
const Camera kFarEdgeView = pannedPaintCamera(glm::vec3(-float(kDefaultSkySpan + 1), 0.0f, 0.0f));

TEST(SkyGrowth, APictureOrModelPlacedPastTheEdgeGrowsTheSkyAndLandsWhole) {
  for (const bool model : {false, true}) {
    SCOPED_TRACE(model ? "model" : "picture");
    const ui::PlaceShape place{model, model ? torusModel() : duckPicture()};
    const Camera view = model ? kFarEdgeView : kEdgeView;
    // Growing (the default), and a session of a 1.4 journal.
    Painter growing, old(strokesOnlySettings());
    const auto t0 = std::chrono::steady_clock::now();
    for (Painter* p : {&growing, &old}) {
      p->apply(ui::SetCamera{view});
      p->apply(place);
    }
    const double ms = msSince(t0) / 2.0;
    const PaintSession& g = growing.session;
    // A sky as wide as the grown one from the start: the same voxel grid.
    PaintSessionSettings wide_settings = productSettings();
    wide_settings.sky_span = wide_settings.sky_max_span = g.sky().span;
    Painter wide(wide_settings);
    wide.apply(ui::SetCamera{view});
    wide.apply(place);
    EXPECT_GT(g.sky().span, kDefaultSkySpan) << "the placement past the edge did not grow the sky";
    EXPECT_EQ(g.skyGrowths(), 1u);
    EXPECT_EQ(g.lastGrowthStroke(), 0u);  // no stroke grew it
    EXPECT_EQ(g.volume().dims(), g.sky().dims());
    EXPECT_EQ(old.session.sky().span, kDefaultSkySpan);
    EXPECT_EQ(old.session.skyGrowths(), 0u);

    // It lands past the old edge, and whole: byte for byte what the sky as wide from the start
    // holds.
    const long long past = voxelsPast(g.volume(), float(kDefaultSkySpan));
    const long long past_old = voxelsPast(old.session.volume(), float(kDefaultSkySpan));
    const long long differing = differingVoxels(g.volume(), wide.session.volume());
    long long voxels = 0;
    const double sum = densitySum(g.volume(), &voxels),
                 sum_wide = densitySum(wide.session.volume()),
                 sum_old = densitySum(old.session.volume());
    std::printf(
        "%s placed across the edge (%.0f ms each): the sky grew to span %d; %lld voxels, %lld "
        "past the old edge (1.4 session: %lld); density %.1f, in a sky that wide from the start "
        "%.1f (%lld voxels differ), clipped %.1f\n",
        model ? "model" : "picture", ms, g.sky().span, voxels, past, past_old, sum, sum_wide,
        differing, sum_old);
    EXPECT_GT(past, voxels / 10) << "nothing landed past the old edge";
    EXPECT_EQ(past_old, 0);
    EXPECT_EQ(differing, 0);
    EXPECT_EQ(volumeChecksum(g.volume()), volumeChecksum(wide.session.volume()));
    EXPECT_LT(sum_old, 0.9 * sum) << "the placement did not reach past the default edge";
  }
}

TEST(SkyGrowth, UndoAndRedoGoOnAcrossAPlacementThatGrewTheSky) {
  Painter p;
  p.stroke(gentleCurve(kW, kH));  // in the home box
  const SkyExtent home_sky = p.session.sky();
  const Volume after_stroke = p.session.volume();
  p.apply(ui::SetCamera{kEdgeView});
  // A picture with no shape is refused before the sky grows: nothing changes.
  const std::string blank = (std::filesystem::temp_directory_path() /
                             ("cb_sky_growth_blank_" + std::to_string(::getpid()) + ".png"))
                                .string();
  ImageRgba8 white;
  white.width = white.height = 32;
  white.pixels.assign(32 * 32 * 4, 255);
  writePng(blank, white);
  std::string error;
  EXPECT_FALSE(p.session.apply(ui::PlaceShape{false, blank}, p.t, &error));
  EXPECT_NE(error.find("no shape pixel"), std::string::npos) << error;
  EXPECT_EQ(p.session.sky().span, home_sky.span);
  std::filesystem::remove(blank);
  p.apply(ui::PlaceShape{false, duckPicture()});  // grows the sky
  const SkyExtent grown_sky = p.session.sky();
  ASSERT_GT(grown_sky.span, home_sky.span);
  const uint64_t after_place = volumeChecksum(p.session.volume());
  const uint64_t stroke_in_grown = volumeChecksum(grownCopy(after_stroke, home_sky, grown_sky));
  ASSERT_NE(after_place, stroke_in_grown);

  p.apply(ui::Undo{});  // the placement: gone, the sky stays grown
  EXPECT_EQ(p.session.sky().span, grown_sky.span);
  EXPECT_EQ(volumeChecksum(p.session.volume()), stroke_in_grown);
  EXPECT_EQ(voxelsPast(p.session.volume(), float(kDefaultSkySpan)), 0);
  p.apply(ui::Undo{});  // the camera
  p.apply(ui::Undo{});  // the stroke
  EXPECT_FALSE(p.session.volume().hasDensity());
  p.apply(ui::Redo{});
  EXPECT_EQ(volumeChecksum(p.session.volume()), stroke_in_grown);
  p.apply(ui::Redo{});
  p.apply(ui::Redo{});
  EXPECT_EQ(volumeChecksum(p.session.volume()), after_place);
  EXPECT_GT(voxelsPast(p.session.volume(), float(kDefaultSkySpan)), 0);
}

// Records camera moves and placements past the sky's edges into a journal at `path` and
// returns the session's checksum.
uint64_t recordPlacements(const PaintSessionSettings& settings, const std::string& path,
                          SkyExtent* sky, uint32_t* growths) {
  Painter p(settings);
  p.session.setReproducibleRecord(true);
  JournalWriter journal;
  EXPECT_TRUE(journal.open(path)) << journal.error();
  p.session.recordTo(&journal, 0);
  p.apply(ui::SetCamera{kEdgeView});
  p.apply(ui::PlaceShape{false, duckPicture()});
  p.apply(ui::SetCamera{kFarEdgeView});
  p.apply(ui::PlaceShape{true, torusModel()});
  journal.close();
  *sky = p.session.sky();
  *growths = p.session.skyGrowths();
  return volumeChecksum(p.session.volume());
}

// CB_KEEP_JOURNALS=DIR keeps a journal as DIR/name (to replay with `cloudbrush replay`, e.g.
// --frames to look at the painter's screen, or with an older build for its checksum).
void keepJournal(const std::string& path, const char* name) {
  if (const char* dir = std::getenv("CB_KEEP_JOURNALS"))
    std::filesystem::copy_file(path, std::string(dir) + "/" + name,
                               std::filesystem::copy_options::overwrite_existing);
}

std::string sessionRecordOf(const std::string& path) {
  for (const JournalRecord& record : readJournal(path).records)
    if (record.type == JournalRecordType::kSession) return std::string(record.text());
  return {};
}

// Replays `path` on 1 and 2 worker threads and checks it ends as recorded.
void expectReplays(const std::string& path, uint64_t sum, const SkyExtent& sky, uint32_t growths) {
  const int threads = workerThreads();
  for (int n : {1, 2}) {
    setWorkerThreads(n);
    const SessionReplay replay = replaySession(readJournal(path), BrushConfig{}, MappingConfig{});
    ASSERT_TRUE(replay.session);
    EXPECT_TRUE(replay.complete())
        << replay.journal_error << (replay.problems.empty() ? "" : replay.problems[0]);
    EXPECT_EQ(replay.session->sky().span, sky.span) << n << " threads";
    EXPECT_EQ(replay.session->skyGrowths(), growths) << n << " threads";
    EXPECT_EQ(volumeChecksum(replay.session->volume()), sum) << n << " threads";
  }
  setWorkerThreads(threads);
}

TEST(SkyGrowth, AJournalWithPlacementsThatGrewTheSkyReplaysByteIdentically) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("cb_sky_growth_place_" + std::to_string(::getpid()) + ".cbj"))
                               .string();
  SkyExtent sky;
  uint32_t growths = 0;
  const uint64_t sum = recordPlacements(productSettings(), path, &sky, &growths);
  EXPECT_EQ(growths, 2u) << "the picture and the model should each grow the sky";
  EXPECT_NE(sessionRecordOf(path).find("placements_grow_sky = true"), std::string::npos)
      << sessionRecordOf(path);
  keepJournal(path, "placements.cbj");
  expectReplays(path, sum, sky, growths);
  std::filesystem::remove(path);
}

// A journal of specification 1.4 (its Session record has sky_max_span but no
// placements_grow_sky): its placements are clipped at the sky's edge, and it replays to the
// checksum cloudbrush gave it before placements grew the sky (measured with the build of
// 2e857b0 by `cloudbrush replay` on the journal this test keeps with CB_KEEP_JOURNALS).
TEST(SkyGrowth, AJournalOfSpecificationOneFourStillClipsItsPlacements) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("cb_sky_growth_place14_" + std::to_string(::getpid()) + ".cbj"))
                               .string();
  SkyExtent sky;
  uint32_t growths = 0;
  const uint64_t sum = recordPlacements(strokesOnlySettings(), path, &sky, &growths);
  const std::string record = sessionRecordOf(path);
  EXPECT_NE(record.find("sky_max_span = 8"), std::string::npos) << record;
  EXPECT_EQ(record.find("placements_grow_sky"), std::string::npos) << record;
  EXPECT_EQ(sky.span, kDefaultSkySpan);
  EXPECT_EQ(growths, 0u);
  std::printf("1.4 journal with two clipped placements: checksum %016llx\n",
              (unsigned long long)sum);
  keepJournal(path, "placements_spec_1_4.cbj");
  EXPECT_EQ(sum, 0x8ae6b72b256d1934ull) << "the clipped placements no longer replay as before";
  expectReplays(path, sum, sky, growths);
  std::filesystem::remove(path);
}

// How two renderers' copies of the same volume differ: occupancy cells, light bricks (values as
// the pool reads them, LightVolume::brickTransmittance, and which bricks are stored), stored
// light depths, bricks with a slot in one only, and bricks whose slots hold other bytes.
struct StateDifferences {
  long long occupancy = 0, light_values = 0, light_bricks = 0, light_depths = 0, slots = 0,
            slot_bytes = 0;
  long long total() const {
    return occupancy + light_values + light_bricks + light_depths + slots + slot_bytes;
  }
};

std::vector<uint8_t> poolTexels(const BrickPool& pool) {
  const glm::ivec3 t = pool.poolTexels();
  std::vector<uint8_t> texels(size_t(t.x) * size_t(t.y) * size_t(t.z) * 4);
  glGetTextureImage(pool.poolTexture(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(texels.size()),
                    texels.data());
  return texels;
}

StateDifferences stateDifferences(const VolumeRenderer& a, const VolumeRenderer& b,
                                  const Volume& volume) {
  StateDifferences d;
  const OccupancyPyramid &oa = a.occupancy(), &ob = b.occupancy();
  if (oa.levels.size() != ob.levels.size()) d.occupancy = 1 << 30;
  for (size_t m = 0; m < std::min(oa.levels.size(), ob.levels.size()); ++m) {
    if (oa.levels[m].size() != ob.levels[m].size()) {
      d.occupancy += 1 << 20;
      continue;
    }
    for (size_t i = 0; i < oa.levels[m].size(); ++i)
      d.occupancy += oa.levels[m][i] != ob.levels[m][i];
  }
  const LightVolume &la = a.lightVolume(), &lb = b.lightVolume();
  const size_t columns = std::max(la.stored_slices.size(), lb.stored_slices.size());
  for (size_t i = 0; i < columns; ++i)
    d.light_depths += i >= la.stored_slices.size() || i >= lb.stored_slices.size() ||
                      la.stored_slices[i] != lb.stored_slices[i];
  const BrickPool &pa = a.brickPool(), &pb = b.brickPool();
  const std::vector<uint8_t> ta = poolTexels(pa), tb = poolTexels(pb);
  const glm::ivec3 bd = volume.brickDims();
  constexpr int S = BrickPool::kSlotTexels;
  for (int z = 0; z < bd.z; ++z)
    for (int y = 0; y < bd.y; ++y)
      for (int x = 0; x < bd.x; ++x) {
        const glm::ivec3 brick(x, y, z);
        const float *va = la.brickTransmittance(brick), *vb = lb.brickTransmittance(brick);
        d.light_values += !va || !vb || !std::equal(va, va + Volume::kBrickVoxels, vb);
        const size_t i = la.lit.brickIndex(brick);
        d.light_bricks += (la.lit.get(i) != nullptr) != (lb.lit.get(i) != nullptr) ||
                          (la.through.get(i) != nullptr) != (lb.through.get(i) != nullptr);
        const glm::u8vec4 sa = pa.slotOf(brick), sb = pb.slotOf(brick);
        if ((sa.w != 0) != (sb.w != 0)) {
          ++d.slots;
          continue;
        }
        if (sa.w == 0) continue;
        bool same = true;
        for (int k = 0; k < S && same; ++k)
          for (int j = 0; j < S && same; ++j) {
            auto row = [&](const std::vector<uint8_t>& t, const BrickPool& p, glm::u8vec4 slot) {
              const glm::ivec3 at = glm::ivec3(slot) * S, n = p.poolTexels();
              return t.data() + ((size_t(at.z + k) * size_t(n.y) + size_t(at.y + j)) * size_t(n.x) +
                                 size_t(at.x)) *
                                    4;
            };
            same = std::equal(row(ta, pa, sa), row(ta, pa, sa) + S * 4, row(tb, pb, sb));
          }
        d.slot_bytes += !same;
      }
  return d;
}

// The largest channel difference between two images of the same size.
int worstPixel(const ImageRgba8& a, const ImageRgba8& b) {
  int worst = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    worst = std::max(worst, std::abs(int(a.pixels[i]) - int(b.pixels[i])));
  return worst;
}

// A stroke that grows the sky does not cost a fresh renderer sync: the renderer that showed the
// sky before shifts what it holds by the growth's offset (Volume::Growth) and updates the
// stroke as an edit. What it then holds and draws equals what a renderer given the grown sky
// afresh holds and draws: occupancy, light (values, stored bricks and depths), the pool's slots
// brick by brick, and the images at the default camera and the two painting views — for the
// default sun (from above: the sweep runs along y) and two low suns (along x, from the low and
// the high side, whose depths count from the side the sky grew on), whose shadows cross the old
// edge into the grown sky.
TEST_F(SkyGrowthGl, TheRendererFollowsTheGrowthAndHoldsWhatAFreshSyncHolds) {
  const std::vector<SyntheticStroke> strokes = referencePaintStrokes(kW, kH);
  const Camera home_view = initialPaintCamera(productSettings());
  const Camera far_view = pannedPaintCamera(glm::vec3(-6.0f, 0.0f, 5.0f));
  struct Sun {
    const char* name;
    Light light;
  };
  std::vector<Sun> suns(3);
  suns[0].name = "default sun";
  suns[1].name = "low sun from -x";
  suns[1].light.direction = glm::normalize(glm::vec3(-1.0f, 0.35f, 0.4f));
  suns[2].name = "low sun from +x";
  suns[2].light.direction = glm::normalize(glm::vec3(1.0f, 0.3f, -0.45f));
  RenderOptions options;
  for (const Sun& sun : suns) {
    SCOPED_TRACE(sun.name);
    Painter p;
    VolumeRenderer followed;
    std::string err;
    ASSERT_TRUE(followed.init(&err)) << err;
    p.stroke(gentleCurve(kW, kH));  // in the home box
    followed.sync(p.session.volume(), sun.light);
    const Camera views[] = {kEdgeView, far_view};
    for (int growth = 0; growth < 2; ++growth) {
      const int span_before = p.session.sky().span;
      p.apply(ui::SetCamera{views[growth]});
      p.stroke(strokes[size_t(growth)]);
      ASSERT_GT(p.session.sky().span, span_before) << "the stroke did not grow the sky";
      const Volume& v = p.session.volume();
      auto t0 = std::chrono::steady_clock::now();
      const SyncStats shifted = followed.sync(v, sun.light);
      const double shifted_ms = msSince(t0);
      EXPECT_TRUE(shifted.followed_growth);
      VolumeRenderer fresh;
      ASSERT_TRUE(fresh.init(&err)) << err;
      t0 = std::chrono::steady_clock::now();
      const SyncStats whole = fresh.sync(v, sun.light);
      const double fresh_ms = msSince(t0);
      EXPECT_FALSE(whole.followed_growth);
      const StateDifferences d = stateDifferences(followed, fresh, v);
      int worst = 0;
      for (const Camera& view : {home_view, kEdgeView, far_view}) {
        followed.render(view, kW, kH, target.fbo(), options);
        const ImageRgba8 a = target.readRgba8();
        fresh.render(view, kW, kH, target.fbo(), options);
        worst = std::max(worst, worstPixel(a, target.readRgba8()));
      }
      std::printf(
          "%s, sky span %d -> %d: followed sync %.1f ms (growth %.1f, light %.1f, pack %.1f, "
          "%d slots uploaded), fresh sync %.1f ms; %zu light bricks, %zu slots; differences: "
          "occupancy %lld, light values %lld, light bricks %lld, depths %lld, slots %lld, slot "
          "bytes %lld; images by at most %d/255\n",
          sun.name, span_before, p.session.sky().span, shifted_ms, shifted.growth_ms,
          shifted.light_ms, shifted.pack_ms, shifted.slots_uploaded, fresh_ms,
          fresh.lightVolume().lit.allocated() + fresh.lightVolume().through.allocated(),
          fresh.brickPool().slotsInUse(), d.occupancy, d.light_values, d.light_bricks,
          d.light_depths, d.slots, d.slot_bytes, worst);
      EXPECT_EQ(d.total(), 0);
      EXPECT_EQ(followed.brickPool().slotsInUse(), fresh.brickPool().slotsInUse());
      EXPECT_LE(worst, 1);
    }
  }
}

}  // namespace
}  // namespace cb
