// The kiosk's attract loop morphs into visitors' gallery clouds after its replay (issues 11 and
// 14): with the bundled attract journal (sped up), a gallery of three entries (the newest does
// not fit the sky) and a ManualClock, the replayed cloud holds, then morphs into the newest
// cloud that fits (the unfitting one named and skipped), holds it — the session's cloud is then
// that gallery cloud — morphs into the next, and the loop starts again on an empty sky. The
// in-betweens move (they are not a cross-fade). Drawn on EGL surfaceless (llvmpipe);
// CB_KEEP_FRAMES=DIR keeps the frames for looking.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <functional>
#include <vector>

#include "app/render/image_io.h"
#include "app/shell/kiosk/attract_screen.h"
#include "app/volume/scene_generators.h"
#include "app/volume/volume_file.h"
#include "tests/support/test_display.h"

namespace cb {
namespace {
namespace fs = std::filesystem;

constexpr int kW = 640, kH = 360, kGrid = 64;

float maxDifference(const Volume& a, const Volume& b) {
  const std::vector<float> da = a.toDense(), db = b.toDense();
  float m = 0;
  for (size_t i = 0; i < da.size(); ++i) m = std::max(m, std::abs(da[i] - db[i]));
  return m;
}

double total(const Volume& v) {
  double s = 0;
  for (float d : v.toDense()) s += d;
  return s;
}

TEST(AttractMorph, TheReplayedCloudMorphsIntoGalleryCloudsThenTheLoopStartsAgain) {
  const std::string dir =
      (fs::temp_directory_path() / ("cb_attract_morph_" + std::to_string(::getpid()))).string();
  fs::remove_all(dir);
  const Volume older = makeBundledCumulus(glm::ivec3(kGrid), 7);
  const Volume newer = makeSparsePuffs(glm::ivec3(kGrid), 3);
  for (const char* entry : {"000001", "000002", "000003"})
    fs::create_directories(dir + "/" + entry);
  saveVolume(older, dir + "/000001/cloud.cbvol");
  saveVolume(newer, dir + "/000002/cloud.cbvol");
  saveVolume(makeSparsePuffs(glm::ivec3(kGrid / 2), 4), dir + "/000003/cloud.cbvol");

  std::string error;
  auto display = test::openTestDisplay(kW, kH, &error);
  ASSERT_TRUE(display) << error;
  VolumeRenderer renderer;
  ASSERT_TRUE(renderer.init(&error)) << error;
  const JournalReadResult journal =
      readJournal(std::string(CB_SOURCE_DIR) + "/config/kiosk/attract.cbj");
  ASSERT_TRUE(journal.error.empty()) << journal.error;
  AttractOptions options;
  options.grid = kGrid;
  options.speed = 50.0;
  options.hold_s = 1.0;
  options.morph_seconds = 2.0;
  options.gallery_dir = dir;
  options.gallery_morphs = 2;
  options.render.scale = 1.0f;  // sharp frames for looking (the kiosk adapts its scale)
  ManualClock clock(1'000'000'000);
  AttractScreen screen(renderer, clock, journal.records, options, nullptr);
  screen.waitUntilPrepared();  // the strokes are mapped on the replay's worker thread
  FrameContext frame{*display, kW, kH};
  auto runUntil = [&](const std::function<bool()>& done, double max_s) {
    for (double t = 0; t < max_s; t += 0.1) {
      clock.advance(100'000'000);
      frame.now_ns = clock.nowNs();
      screen.update(frame);
      ++frame.frame;
      if (done()) return true;
    }
    return false;
  };
  auto run = [&](double seconds) { runUntil([] { return false; }, seconds); };
  auto keep = [&](const std::string& name) {
    ASSERT_TRUE(screen.draw(frame, &error)) << error;
    ImageRgba8 image;
    image.width = kW;
    image.height = kH;
    ASSERT_TRUE(display->readPixels(&image.pixels));
    if (const char* keep_dir = std::getenv("CB_KEEP_FRAMES"))
      writePng(std::string(keep_dir) + "/" + name, image);
  };

  ASSERT_TRUE(runUntil([&] { return screen.recordsPlayed() == screen.recordCount(); }, 120));
  const Volume replayed = screen.volume();
  ASSERT_GT(total(replayed), 0.0);
  keep("attract_morph_0_replayed.png");
  // Held, then the first morph: into 000002 (000003, the newest, does not fit and is named).
  ASSERT_TRUE(runUntil([&] { return screen.morphing(); }, 3));
  EXPECT_EQ(screen.lastGalleryShown(), 2);
  ASSERT_EQ(screen.problems().size(), 1u);
  EXPECT_NE(screen.problems()[0].find("000003"), std::string::npos) << screen.problems()[0];
  run(1.0);  // half way through the morph
  const Volume& middle = screen.shownVolume();
  EXPECT_GT(maxDifference(middle, replayed), 0.05f);
  EXPECT_GT(maxDifference(middle, newer), 0.05f);
  Volume fade(middle.dims(), middle.worldMin(), middle.worldMax());
  const std::vector<float> dr = replayed.toDense(), dn = newer.toDense();
  std::vector<float> blended(dr.size());
  for (size_t i = 0; i < blended.size(); ++i) blended[i] = 0.5f * (dr[i] + dn[i]);
  fade.assignDense(blended.data());
  EXPECT_GT(maxDifference(middle, fade), 0.05f) << "an in-between, not a cross-fade";
  keep("attract_morph_1_halfway.png");
  // Played and held: the session's cloud is the gallery cloud; the next morph (into 000001).
  ASSERT_TRUE(runUntil([&] { return screen.morphsThisLoop() == 2; }, 6));
  EXPECT_LE(maxDifference(screen.volume(), newer), 1.0f / 255.0f);
  EXPECT_EQ(screen.lastGalleryShown(), 1);
  run(2.5);  // played to the end, held
  keep("attract_morph_2_second_gallery_cloud.png");
  // Two morphs a loop: then the replay starts again on an empty sky.
  ASSERT_TRUE(runUntil([&] { return screen.loopsCompleted() == 1; }, 3));
  EXPECT_EQ(total(screen.volume()), 0.0);
  EXPECT_FALSE(screen.morphing());
  EXPECT_EQ(screen.problems().size(), 1u);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace cb
