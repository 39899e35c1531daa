// Undo/redo: N strokes undone and redone give byte-identical volumes and light volumes, held as
// compressed brick deltas far smaller than whole volumes.
#include <gtest/gtest.h>

#include <cstring>

#include "app/render/light_volume.h"
#include "app/session/paint_session.h"
#include "app/session/synthetic_session.h"

namespace cb {
namespace {

constexpr int kW = 320, kH = 180, kGrid = 64;

bool sameBytes(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

std::vector<float> voxels(const Volume& v) {
  return v.toDense();
}

// Follows the volume's dirty boxes the way the renderer does.
struct LightFollower {
  LightVolume light_volume;
  uint64_t seen = 0;
  void sync(const Volume& volume, const Light& light) {
    sweepLightVolume(light_volume, volume, light,
                     seen == 0 ? volume.bounds() : volume.dirtySince(seen));
    seen = volume.generation();
  }
};

std::vector<float> freshLight(const Volume& volume, const Light& light) {
  LightVolume lv;
  sweepLightVolume(lv, volume, light, volume.bounds());
  return lv.toDense();
}

TEST(History, UndoThenRedoOfEveryStrokeIsByteIdenticalForVolumeAndLight) {
  PaintSession session({kW, kH, kGrid}, BrushConfig{}, MappingConfig{});
  session.setQuietMapping(true);
  const PenDeviceInfo tablet = syntheticTablet(kW, kH);
  session.setDevice(tablet, 0);
  LightFollower follower;
  follower.sync(session.volume(), session.light());
  std::vector<std::vector<float>> after_stroke{voxels(session.volume())};
  std::vector<std::vector<float>> light_after{follower.light_volume.toDense()};
  int64_t t0 = 1'000'000'000;
  const std::vector<SyntheticStroke> strokes = referencePaintStrokes(kW, kH);
  for (int round = 0; round < 2; ++round)
    for (const SyntheticStroke& stroke : strokes) {
      for (const PenSample& s : syntheticPenSamples(stroke, tablet, kW, kH, 200.0, t0)) {
        session.feed(s);
        t0 = s.t_ns;
      }
      t0 += 100'000'000;
      follower.sync(session.volume(), session.light());
      after_stroke.push_back(voxels(session.volume()));
      light_after.push_back(follower.light_volume.toDense());
    }
  const size_t n = after_stroke.size() - 1;
  ASSERT_EQ(session.strokesMapped(), n);
  ASSERT_EQ(session.history().undoable(), n);
  EXPECT_FALSE(sameBytes(after_stroke[0], after_stroke[n])) << "the strokes painted something";
  for (size_t i = n; i > 0; --i) {
    std::string error;
    ASSERT_TRUE(session.apply(ui::Undo{}, t0, &error)) << error;
    follower.sync(session.volume(), session.light());
    EXPECT_TRUE(sameBytes(voxels(session.volume()), after_stroke[i - 1])) << "undo to " << i - 1;
    EXPECT_TRUE(sameBytes(follower.light_volume.toDense(), light_after[i - 1]))
        << "light after undo to " << i - 1;
  }
  std::string error;
  EXPECT_FALSE(session.apply(ui::Undo{}, t0, &error));
  for (size_t i = 1; i <= n; ++i) {
    ASSERT_TRUE(session.apply(ui::Redo{}, t0, &error)) << error;
    follower.sync(session.volume(), session.light());
    EXPECT_TRUE(sameBytes(voxels(session.volume()), after_stroke[i])) << "redo to " << i;
    EXPECT_TRUE(sameBytes(follower.light_volume.toDense(), light_after[i]));
  }
  // The incrementally followed light equals a fresh sweep of the final volume.
  EXPECT_TRUE(
      sameBytes(follower.light_volume.toDense(), freshLight(session.volume(), session.light())));
  // Deltas are a small part of what whole volumes would hold.
  const size_t whole = n * session.volume().voxelCount() * sizeof(float);
  EXPECT_LT(session.history().deltaBytes() * 10, whole) << session.history().deltaBytes();
  std::printf("%zu strokes: %zu bytes of deltas (whole volumes: %zu)\n", n,
              session.history().deltaBytes(), whole);
}

TEST(History, SceneChangesUndoAndANewStepDropsRedo) {
  PaintSession session({kW, kH, kGrid}, BrushConfig{}, MappingConfig{});
  const Canvas before = session.canvas();
  std::string error;
  ASSERT_TRUE(session.apply(ui::SetCanvas{0.3f, 0.2f}, 0, &error)) << error;
  ASSERT_TRUE(session.apply(ui::SetLight{glm::vec3(0, 1, 0), glm::vec3(1, 0.5f, 0.5f)}, 0, &error));
  ASSERT_TRUE(session.apply(ui::Undo{}, 0, &error)) << error;
  EXPECT_NE(session.light().direction, glm::vec3(0, 1, 0));
  EXPECT_EQ(session.canvas().altitude, 0.3f);
  ASSERT_TRUE(session.apply(ui::Undo{}, 0, &error)) << error;
  EXPECT_EQ(session.canvas().altitude, before.altitude);
  ASSERT_TRUE(session.apply(ui::Redo{}, 0, &error)) << error;
  EXPECT_EQ(session.canvas().altitude, 0.3f);
  ASSERT_TRUE(session.apply(ui::SetCanvas{-0.2f, 0.2f}, 0, &error));
  EXPECT_FALSE(session.apply(ui::Redo{}, 0, &error)) << "a new step forgets the redo";
}

}  // namespace
}  // namespace cb
