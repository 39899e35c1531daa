// The brush size (ui::SetBrushSize, brush.toml stroke.size): the footprint is the screen ÷ the
// size, the mark and its cloud grow with it, the size is journalled at the start and at every
// change, and a journal replays at the sizes it was painted with whatever the replaying
// machine's brush.toml says.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "app/session/paint_session.h"
#include "app/session/session_replay.h"
#include "app/session/synthetic_session.h"
#include "tests/support/session_painter.h"

namespace cb {
namespace {

constexpr int kW = 320, kH = 180, kGrid = 64;

long long cloudVoxels(const Volume& v) {
  long long n = 0;
  for (float d : v.toDense()) n += d > 0.05f;
  return n;
}

BrushConfig sized(float size) {
  BrushConfig brush;
  brush.stroke.size = size;
  return brush;
}

TEST(BrushSize, TheFootprintIsTheScreenDividedByTheSizeAndTheCloudGrows) {
  const SyntheticStroke stroke = referencePaintStrokes(kW, kH)[0];
  test::SessionPainter one({kW, kH, kGrid}, sized(1.0f), MappingConfig{});
  test::SessionPainter two({kW, kH, kGrid}, sized(2.0f), MappingConfig{});
  EXPECT_EQ(one.session.footprintWidth(), kW);
  EXPECT_EQ(two.session.footprintWidth(), kW / 2);
  EXPECT_EQ(two.session.footprintHeight(), kH / 2);
  one.stroke(stroke);
  two.stroke(stroke);
  const long long small = cloudVoxels(one.session.volume());
  const long long large = cloudVoxels(two.session.volume());
  ASSERT_GT(small, 0);
  // Twice as wide and (spheres) twice as thick along the same length: about 4× the voxels;
  // at least 2.5× leaves room for the rims' voxel rounding on a 64-grid.
  EXPECT_GE(double(large), 2.5 * double(small)) << small << " -> " << large;
}

TEST(BrushSize, IsJournalledAndReplaysAtTheRecordedSizes) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("cb_brush_size_" + std::to_string(::getpid()) + ".cbj"))
                               .string();
  const std::vector<SyntheticStroke> strokes = referencePaintStrokes(kW, kH);
  uint64_t sum = 0;
  {
    test::SessionPainter p({kW, kH, kGrid}, sized(3.0f), MappingConfig{});
    JournalWriter journal;
    ASSERT_TRUE(journal.open(path)) << journal.error();
    p.session.recordTo(&journal, 0);
    p.stroke(strokes[0]);
    p.apply(ui::SetBrushSize{steppedBrushSize(3.0f, -2)});
    EXPECT_FLOAT_EQ(p.session.brushSize(), 3.0f / 1.5625f);
    p.stroke(strokes[1]);
    journal.close();
    sum = volumeChecksum(p.session.volume());
  }
  // Replayed with a local brush.toml of another size: the journal's sizes win.
  const SessionReplay replay = replaySession(readJournal(path), sized(1.0f), MappingConfig{});
  ASSERT_TRUE(replay.session);
  EXPECT_TRUE(replay.complete()) << replay.journal_error
                                 << (replay.problems.empty() ? "" : replay.problems[0]);
  EXPECT_EQ(replay.session->brushSize(), steppedBrushSize(3.0f, -2));
  EXPECT_EQ(volumeChecksum(replay.session->volume()), sum);
  std::filesystem::remove(path);
}

TEST(BrushSize, StepsAreClampedToTheRange) {
  EXPECT_FLOAT_EQ(steppedBrushSize(1.0f, 1), kBrushSizeStep);
  EXPECT_EQ(steppedBrushSize(kMaxBrushSize, 1), kMaxBrushSize);
  EXPECT_EQ(steppedBrushSize(kMinBrushSize, -1), kMinBrushSize);
  EXPECT_FLOAT_EQ(steppedBrushSize(steppedBrushSize(2.0f, 3), -3), 2.0f);
}

}  // namespace
}  // namespace cb
