// The attract loop's replay on its worker thread (app/shell/attract_replay.h), with the bundled
// attract journal at the kiosk's grid:
//   - the worker's final cloud is the one `cloudbrush replay` gives (same checksum as applying
//     every record in order on this thread), and each keyframe's cloud is what the journal had
//     made by then;
//   - the attract screen's update() never maps a stroke: driven by a clock that jumps half a
//     second per frame through the whole journal, no update takes more than a few milliseconds,
//     where mapping a stroke in the loop took about 0.1–0.3 s here (6–19 s per frame in the
//     emulated kiosk of tests/hil/kms);
//   - while the worker is behind the clock, the replay holds instead of skipping records.
#include "app/shell/attract_replay.h"

#include <gtest/gtest.h>

#include <chrono>

#include "app/session/session_replay.h"
#include "app/shell/attract_screen.h"
#include "tests/support/test_display.h"

namespace cb {
namespace {

constexpr int kGrid = 128;

double density(const Volume& v) {
  double s = 0;
  for (float d : v.toDense()) s += d;
  return s;
}

struct Bundled {
  std::vector<JournalRecord> records;
  RecordedSettings recorded;
};

Bundled bundledJournal() {
  Bundled b;
  JournalReadResult journal = readJournal(std::string(CB_SOURCE_DIR) + "/config/kiosk/attract.cbj");
  EXPECT_TRUE(journal.error.empty()) << journal.error;
  b.records = std::move(journal.records);
  b.recorded = recordedSettings(b.records, BrushConfig{}, MappingConfig{});
  b.recorded.settings.grid = kGrid;
  return b;
}

TEST(AttractReplay, TheWorkersCloudIsTheJournalsAndKeyframesFollowIt) {
  const Bundled b = bundledJournal();
  ASSERT_GT(b.records.size(), 500u);
  AttractReplay replay(b.records, b.recorded.settings, b.recorded.brush, b.recorded.mapping,
                       Light{});
  EXPECT_EQ(replay.keyframeAt(0).records, 0u);
  EXPECT_EQ(density(*replay.keyframeAt(0).volume), 0.0) << "the first keyframe is the empty sky";
  // The same records applied here, in order (what the attract loop did in its frames before).
  PaintSession direct(b.recorded.settings, b.recorded.brush, b.recorded.mapping);
  direct.setQuietMapping(true);
  std::vector<std::pair<size_t, uint64_t>> after_strokes;  // records applied, checksum
  uint64_t generation = direct.volume().generation();
  for (size_t i = 0; i < b.records.size(); ++i) {
    std::string error;
    if (b.records[i].type != JournalRecordType::kSession) {
      ASSERT_TRUE(direct.applyRecord(b.records[i], nullptr, &error)) << i << ": " << error;
    }
    if (direct.volume().generation() != generation) {
      generation = direct.volume().generation();
      after_strokes.emplace_back(i + 1, volumeChecksum(direct.volume()));
    }
  }
  ASSERT_GE(after_strokes.size(), 3u);
  replay.waitUntilFinished();
  EXPECT_TRUE(replay.finished());
  EXPECT_TRUE(replay.problems().empty()) << replay.problems().front();
  for (const auto& [records, checksum] : after_strokes) {
    EXPECT_EQ(volumeChecksum(*replay.keyframeAt(records).volume), checksum) << records;
    EXPECT_NE(volumeChecksum(*replay.keyframeAt(records - 1).volume), checksum)
        << "the cloud changes at record " << records << ", not before";
  }
  EXPECT_EQ(volumeChecksum(*replay.keyframeAt(b.records.size()).volume),
            volumeChecksum(direct.volume()));
}

TEST(AttractReplay, TheAttractScreensUpdateNeverWaitsForAMapping) {
  const Bundled b = bundledJournal();
  AttractOptions options;
  options.grid = kGrid;
  options.speed = 1.5;  // config/kiosk.toml
  options.hold_s = 2.0;
  ManualClock clock(1'000'000'000);
  std::string error;
  auto display = test::openTestDisplay(320, 180, &error);
  ASSERT_TRUE(display) << error;
  VolumeRenderer renderer;  // update() does not draw
  AttractScreen screen(renderer, clock, b.records, options, nullptr);
  FrameContext frame{*display, 320, 180};
  // Right away, before the worker has mapped anything much: the clock jumps past the whole
  // journal, and the replay holds at what is mapped instead of skipping to the end.
  clock.advance(120'000'000'000);
  screen.update(frame);
  const size_t first = screen.recordsPlayed();
  EXPECT_LT(first, screen.recordCount()) << "the worker cannot have mapped 5 strokes at once";
  screen.waitUntilPrepared();
  // Then half a second per frame through the journal and the hold (a slow machine's frames).
  double longest_ms = 0.0, total_ms = 0.0;
  long updates = 0;
  for (int i = 0; i < 400 && screen.loopsCompleted() == 0; ++i) {
    clock.advance(500'000'000);
    const auto t0 = std::chrono::steady_clock::now();
    screen.update(frame);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    longest_ms = std::max(longest_ms, ms);
    total_ms += ms;
    ++updates;
  }
  EXPECT_EQ(screen.loopsCompleted(), 1);
  std::printf("attract update over a whole loop: %ld updates, longest %.3f ms, total %.3f ms\n",
              updates, longest_ms, total_ms);
  EXPECT_LT(longest_ms, 50.0) << "an update mapped a stroke";
  // Played through: the journal's records, in order, then the next loop from the empty sky.
  EXPECT_EQ(screen.recordsPlayed(), 0u);
  EXPECT_EQ(density(screen.volume()), 0.0);
}

}  // namespace
}  // namespace cb
