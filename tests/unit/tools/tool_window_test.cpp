// Morph and wind in a sky wider than one box work on a window of it (tool_window.h).
// At grid 64 and span 4 (a 256×64×256 sky over [-4,4]×[-1,1]×[-4,4]; grid 64 for speed, the
// rule is the same at 256): the window is the whole volume for one-box skies and other volumes;
// it follows the content otherwise (the home-box tile, another tile, an edge tile, a home box
// centred on a cloud across tiles, or the content's own box, at least a home box across, with
// 64 wind cells per home box); a morph and a wind run on a cloud give the same bytes, translated,
// as the same run on the one-box 64³ volume, wherever the cloud sits; pasting back marks only
// the bricks that changed; the half-resolution copy computed brick by brick is the straightforward
// one; and in a span-4 session a recorded morph and wind replay to the same checksum on 1 and 8
// threads, the home-box session's cloud being the one-box session's, translated.
#include <bit>
#include <cstring>
#include <filesystem>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include "app/core/parallel_for.h"
#include "app/session/paint_session.h"
#include "app/session/session_replay.h"
#include "app/shell/painter/animation_preview.h"
#include "app/tools/cloud_animation.h"
#include "app/tools/tool_window.h"
#include "app/volume/scene_generators.h"
#include "app/volume/sky_extent.h"
#include "app/volume/volume_file.h"

namespace cb {
namespace {

constexpr int kGrid = 64;
const SkyExtent kSky{kGrid, 4};

bool sameBytes(const Volume& a, const Volume& b) {
  return a.dims() == b.dims() &&
         std::memcmp(a.toDense().data(), b.toDense().data(), a.voxelCount() * sizeof(float)) == 0;
}

// `cloud` (any dims) written into `into` at `offset`.
void placeAt(const Volume& cloud, glm::ivec3 offset, Volume* into) {
  const glm::ivec3 d = cloud.dims();
  std::vector<float> row(size_t(d.x));
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y) {
      cloud.readLine({0, y, z}, 0, d.x, row.data());
      into->writeLine(offset + glm::ivec3(0, y, z), 0, d.x, row.data());
    }
  into->markDirty(into->bounds());
}

// The one-box clouds: a small cumulus and puffs (32³) in the middle of a 64³ box, so their
// content with its margin stays inside the box.
struct OneBox {
  Volume source{glm::ivec3(kGrid)}, target{glm::ivec3(kGrid)};
  OneBox() {
    placeAt(makeBundledCumulus(glm::ivec3(32), 1), glm::ivec3(16), &source);
    placeAt(makeSparsePuffs(glm::ivec3(32), 2), glm::ivec3(16), &target);
  }
};

// The one-box volume's voxels placed at `at` in an empty span-4 sky.
Volume inSky(const Volume& one_box, glm::ivec3 at) {
  Volume sky = makeSkyVolume(kSky);
  placeAt(one_box, at, &sky);
  return sky;
}

Volume cropBytes(const Volume& v, glm::ivec3 at, glm::ivec3 dims) {
  return cropToWindow(v, {at, at + dims}, glm::vec3(-1.0f), glm::vec3(1.0f));
}

WindRun testRun() {
  WindRun run;
  run.segments = {{1.0f, 0.0f, 6}, {0.0f, -1.0f, 4}};
  return run;
}

TEST(ToolWindow, AOneBoxSkyOrAnyOtherVolumeIsWorkedOnWhole) {
  Volume box{glm::ivec3(kGrid)};
  box.set(3, 4, 5, 1.0f);
  Volume one_box_sky = makeSkyVolume({kGrid, 1});
  one_box_sky.set(3, 4, 5, 1.0f);
  Volume wide_not_sky(glm::ivec3(4 * kGrid, kGrid, 4 * kGrid));  // over [-1,1]³: not a sky
  wide_not_sky.set(3, 4, 5, 1.0f);
  for (const Volume* v : {&box, &one_box_sky, &wide_not_sky}) {
    const ToolWindow w = toolWindow(*v);
    EXPECT_TRUE(w.whole);
    EXPECT_EQ(w.box, v->bounds());
    EXPECT_EQ(w.world_min, v->worldMin());
    EXPECT_EQ(w.world_max, v->worldMax());
    EXPECT_EQ(w.wind_cells, glm::ivec3(64));
  }
}

TEST(ToolWindow, TheWindowFollowsTheContent) {
  const glm::ivec3 home = kSky.homeOffset();  // (96, 0, 96)
  ASSERT_EQ(home, glm::ivec3(96, 0, 96));
  OneBox c;
  struct Case {
    const char* name;
    glm::ivec3 at;        // where the one-box volume's corner goes
    glm::ivec3 lo, size;  // the window expected
  } cases[] = {
      {"home box", home, home, glm::ivec3(kGrid)},
      {"a tile east and north", home + glm::ivec3(64, 0, -64), {160, 0, 32}, glm::ivec3(kGrid)},
      {"the edge tiles", {192, 0, 0}, {192, 0, 0}, glm::ivec3(kGrid)},
      // Content [144,176) + margin 16 = [128,192): in no tile, a home box centred on it.
      {"across tiles", home + glm::ivec3(32, 0, 0), {128, 0, 96}, glm::ivec3(kGrid)},
  };
  for (const Case& k : cases) {
    const ToolWindow w = toolWindow(inSky(c.source, k.at));
    EXPECT_FALSE(w.whole) << k.name;
    EXPECT_EQ(w.box.lo, k.lo) << k.name;
    EXPECT_EQ(w.dims(), k.size) << k.name;
    EXPECT_EQ(w.wind_cells, glm::ivec3(64)) << k.name;
    EXPECT_EQ(w.world_max - w.world_min, glm::vec3(2.0f)) << k.name;
    EXPECT_FLOAT_EQ(w.gust_radius, 0.5f) << k.name;
  }
  // Two clouds far apart: their union's box with the margin, snapped to bricks; 64 wind cells
  // per home box (one per voxel at grid 64).
  Volume both = inSky(c.source, {0, 0, 0});
  placeAt(c.target, {192, 0, 96}, &both);
  const ToolWindow w = toolWindow(both);
  EXPECT_EQ(w.box.lo, glm::ivec3(0, 0, 0));
  EXPECT_EQ(w.box.hi, glm::ivec3(256, 64, 160));  // the puffs end at z 96 + 48, + 16
  EXPECT_EQ(w.wind_cells, w.dims());
  // A morph's window holds source and target.
  const Volume s = inSky(c.source, {0, 0, 0}), t = inSky(c.target, {192, 0, 96});
  EXPECT_EQ(toolWindow(s, t).box, w.box);
  // At grid 256 (a 1024×256×1024 sky) a home-box cloud's window is 256³ with 64³ cells, and a
  // window twice a home box across has twice the cells.
  Volume big = makeSkyVolume({256, 4});
  big.set(512, 100, 512, 1.0f);
  EXPECT_EQ(toolWindow(big).box, (VoxelBox{{384, 0, 384}, {640, 256, 640}}));
  EXPECT_EQ(toolWindow(big).wind_cells, glm::ivec3(64));
  big.set(512 + 300, 100, 512, 1.0f);
  // Bricks [512, 816) with the margin of 32: [480, 848), 368 voxels, 92 cells.
  EXPECT_EQ(toolWindow(big).box.lo.x, 480);
  EXPECT_EQ(toolWindow(big).dims().x, 368);
  EXPECT_EQ(toolWindow(big).wind_cells, glm::ivec3(92, 64, 64));
}

TEST(ToolWindow, MorphAndWindAreTheOneBoxRunTranslatedWhereverTheCloudSits) {
  OneBox c;
  const float t = 0.35f;
  const WindowFrame morph_one_box = morphFrame(c.source, c.target, t);
  const WindowFrame wind_one_box = windFrame(testRun(), c.source);
  ASSERT_EQ(morph_one_box.at, glm::ivec3(0));
  ASSERT_GT(volumeChecksum(morph_one_box.volume), 0u);
  const glm::ivec3 home = kSky.homeOffset();
  for (const glm::ivec3 at :
       {home, home + glm::ivec3(64, 0, -64), glm::ivec3(192, 0, 0), home + glm::ivec3(32, 0, 0)}) {
    const Volume source = inSky(c.source, at), target = inSky(c.target, at);
    const WindowFrame m = morphFrame(source, target, t);
    EXPECT_EQ(m.at, at);
    EXPECT_TRUE(sameBytes(m.volume, morph_one_box.volume)) << at.x << "," << at.z;
    const WindowFrame w = windFrame(testRun(), source);
    EXPECT_EQ(w.at, at);
    EXPECT_TRUE(sameBytes(w.volume, wind_one_box.volume)) << at.x << "," << at.z;
    // In place: the window's bytes are the one-box result, everything else stays empty.
    Volume blown = source;
    blowWind(testRun(), &blown);
    EXPECT_TRUE(sameBytes(cropBytes(blown, at, glm::ivec3(kGrid)), wind_one_box.volume));
    const VoxelBox content = densityBricks(blown);
    EXPECT_EQ(content.intersect({at, at + kGrid}), content) << "nothing outside the window";
  }
  EXPECT_FALSE(sameBytes(wind_one_box.volume, c.source)) << "the wind moved the cloud";
}

TEST(ToolWindow, PastingBackMarksOnlyTheBricksThatChanged) {
  OneBox c;
  const Volume before = inSky(c.source, kSky.homeOffset() + glm::ivec3(64, 0, 0));
  Volume after = before;
  const uint64_t generation = after.generation();
  blowWind(testRun(), &after);
  std::set<std::tuple<int, int, int>> marked, differ;
  for (const glm::ivec3 b : after.changedBricksSince(generation)) marked.insert({b.x, b.y, b.z});
  const glm::ivec3 nb = after.brickDims();
  for (int z = 0; z < nb.z; ++z)
    for (int y = 0; y < nb.y; ++y)
      for (int x = 0; x < nb.x; ++x) {
        const VoxelBox box = after.brickBox({x, y, z});
        bool same = true;
        for (int k = box.lo.z; k < box.hi.z && same; ++k)
          for (int j = box.lo.y; j < box.hi.y && same; ++j)
            for (int i = box.lo.x; i < box.hi.x && same; ++i)
              same = std::bit_cast<uint32_t>(after.at(i, j, k)) ==
                     std::bit_cast<uint32_t>(before.at(i, j, k));
        if (!same) differ.insert({x, y, z});
      }
  EXPECT_FALSE(differ.empty());
  EXPECT_EQ(marked, differ) << "exactly the bricks that changed are dirty";
  EXPECT_LE(differ.size(), size_t(4 * 4 * 4)) << "within the window's 4x4x4 bricks";
}

TEST(ToolWindow, TheHalfResolutionCopyIsTheStraightforwardOneAndItsWindowIsTheWindowsCopy) {
  OneBox c;
  Volume sky = inSky(c.source, {192, 0, 16});
  placeAt(c.target, {40, 0, 120}, &sky);
  sky.set(255, 63, 255, 0.5f);  // the last voxel of each axis
  const Volume half = halfResolution(sky);
  const glm::ivec3 d = sky.dims(), h = half.dims();
  ASSERT_EQ(h, (d + 1) / 2);
  for (int z = 0; z < h.z; ++z)
    for (int y = 0; y < h.y; ++y)
      for (int x = 0; x < h.x; ++x) {
        float sum = 0.0f;
        int n = 0;
        for (int k = 0; k < 2; ++k)
          for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i)
              if (2 * x + i < d.x && 2 * y + j < d.y && 2 * z + k < d.z) {
                sum += sky.at(2 * x + i, 2 * y + j, 2 * z + k);
                ++n;
              }
        const float expected = sum != 0.0f ? sum / float(n) : 0.0f;
        ASSERT_EQ(std::bit_cast<uint32_t>(half.at(x, y, z)), std::bit_cast<uint32_t>(expected))
            << x << "," << y << "," << z;
      }
  EXPECT_LE(half.allocatedBricks(), sky.allocatedBricks()) << "only under allocated bricks";
  const ToolWindow w = toolWindow(sky);
  EXPECT_TRUE(sameBytes(cropToWindow(half, halfBox(w.box), w.world_min, w.world_max),
                        halfResolution(cropToWindow(sky, w))));
}

// A session's journal directory with the clouds it opens.
struct Files {
  std::string dir;
  explicit Files(const char* name) {
    dir = (std::filesystem::temp_directory_path() /
           (std::string("cb_tool_window_") + name + "_" + std::to_string(::getpid())))
              .string();
    std::filesystem::create_directories(dir);
  }
  ~Files() { std::filesystem::remove_all(dir); }
};

// Morphs the session's cloud into the cloud saved at `target_path` to t = 0.45 and applies it;
// the window it worked on goes to *window.
void morph(PaintSession* s, const std::string& target_path, ToolWindow* window) {
  std::string error;
  AnimationPreview preview;
  ASSERT_TRUE(preview.startMorph(*s, target_path, 1.0, &error)) << error;
  for (int i = 0; i < 3; ++i) preview.advance(0.15);
  EXPECT_NEAR(preview.morphT(), 0.45f, 1e-5f);
  *window = preview.window();
  const uint64_t shown = volumeChecksum(preview.shown());
  ASSERT_TRUE(preview.apply(s, 1000, &error)) << error;
  EXPECT_EQ(volumeChecksum(s->volume()), shown) << "the frame shown was committed";
}

// Blows the wind 7 steps (turning once) and applies it.
void blow(PaintSession* s, ToolWindow* window) {
  std::string error;
  AnimationPreview preview;
  ASSERT_TRUE(preview.toggleWind(*s, &error)) << error;
  for (int i = 0; i < 4; ++i) preview.advance(0.05);
  preview.nextWindDirection();
  for (int i = 0; i < 3; ++i) preview.advance(0.05);
  *window = preview.window();
  const uint64_t shown = volumeChecksum(preview.shown());
  ASSERT_TRUE(preview.apply(s, 2000, &error)) << error;
  EXPECT_EQ(volumeChecksum(s->volume()), shown) << "the wind shown was committed";
}

TEST(ToolWindow, AMorphAndWindRecordedInAWideSkyReplayExactly) {
  Files f("replay");
  OneBox c;
  const std::string target_path = f.dir + "/target.vol", source_path = f.dir + "/source.vol";
  saveVolume(c.target, target_path);  // one-box clouds: they open and morph into the home box
  saveVolume(c.source, source_path);
  std::string error;

  // A cloud opened in the home box: the span-4 session's cloud is the span-1 session's,
  // translated (the windows are the home box) after the morph, and after the wind on the cloud.
  PaintSessionSettings one_box_settings{320, 180, kGrid};
  one_box_settings.sky_span = one_box_settings.sky_max_span = 1;
  PaintSession one_box(one_box_settings, BrushConfig{}, MappingConfig{});
  PaintSession home(PaintSessionSettings{320, 180, kGrid}, BrushConfig{}, MappingConfig{});
  ASSERT_EQ(home.volume().dims(), kSky.dims());
  const VoxelBox home_box{kSky.homeOffset(), kSky.homeOffset() + kGrid};
  ToolWindow window;
  for (PaintSession* s : {&one_box, &home}) {
    ASSERT_TRUE(s->replaceVolume(c.source, 0, source_path, &error)) << error;
    morph(s, target_path, &window);
    EXPECT_EQ(window.box, s == &home ? home_box : one_box.volume().bounds());
  }
  EXPECT_TRUE(
      sameBytes(cropBytes(home.volume(), home_box.lo, glm::ivec3(kGrid)), one_box.volume()));
  EXPECT_FALSE(sameBytes(one_box.volume(), c.source)) << "the morph changed the cloud";
  for (PaintSession* s : {&one_box, &home}) {
    ASSERT_TRUE(s->apply(ui::Undo{}, 1500, &error)) << error;
    blow(s, &window);
    EXPECT_EQ(window.box, s == &home ? home_box : one_box.volume().bounds());
  }
  EXPECT_TRUE(
      sameBytes(cropBytes(home.volume(), home_box.lo, glm::ivec3(kGrid)), one_box.volume()));
  EXPECT_FALSE(sameBytes(one_box.volume(), c.source)) << "the wind changed the cloud";

  // A cloud at the sky's edge, morphed into the home box (a window over both, 160 voxels and
  // cells across), then blown; recorded and replayed on 1 and 8 threads.
  JournalWriter journal;
  const std::string journal_path = f.dir + "/session.cbj";
  ASSERT_TRUE(journal.open(journal_path));
  PaintSession edge(PaintSessionSettings{320, 180, kGrid}, BrushConfig{}, MappingConfig{});
  edge.recordTo(&journal, 0);
  const std::string edge_path = f.dir + "/edge.vol";
  saveVolume(inSky(c.source, {192, 0, 0}), edge_path);
  ASSERT_TRUE(edge.replaceVolume(loadVolume(edge_path), 0, edge_path, &error)) << error;
  morph(&edge, target_path, &window);
  EXPECT_EQ(window.box, (VoxelBox{{96, 0, 0}, {256, 64, 160}}));
  EXPECT_EQ(window.wind_cells, glm::ivec3(160, 64, 160));
  blow(&edge, &window);
  EXPECT_FALSE(window.whole);
  journal.close();
  const uint64_t final_sum = volumeChecksum(edge.volume());
  const JournalReadResult read = readJournal(journal_path);
  for (int threads : {1, 8}) {
    setWorkerThreads(threads);
    const SessionReplay replay = replaySession(read, BrushConfig{}, MappingConfig{});
    ASSERT_TRUE(replay.session);
    EXPECT_TRUE(replay.complete())
        << (replay.problems.empty() ? replay.journal_error : replay.problems[0]);
    EXPECT_EQ(volumeChecksum(replay.session->volume()), final_sum) << threads << " threads";
  }
  setWorkerThreads(0);
}

}  // namespace
}  // namespace cb
