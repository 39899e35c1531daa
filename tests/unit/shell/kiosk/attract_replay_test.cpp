// The attract loop's replay on its worker thread (app/shell/kiosk/attract_replay.h), with the bundled
// attract journal at the kiosk's grid:
//   - the worker's final cloud is the one `cloudbrush replay` gives (same checksum as applying
//     every record in order on this thread), and each keyframe's cloud is what the journal had
//     made by then;
//   - the attract screen's update() never maps a stroke: driven by a clock that jumps half a
//     second per frame through the whole journal, no update takes more than a few milliseconds,
//     where mapping a stroke in the loop took about 0.1–0.3 s here (6–19 s per frame in the
//     emulated kiosk of tests/hil/kms);
//   - while the worker is behind the clock, the replay holds instead of skipping records;
//   - a long attract journal (strokes all over the screen, generated here) keeps the clouds its
//     keyframes hold within the budget plus the newest cloud, where a copy per stroke held the
//     sum of every cloud so far (growing with the square of the journal's length).
#include "app/shell/kiosk/attract_replay.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>

#include <unistd.h>

#include "app/session/session_replay.h"
#include "app/session/synthetic_session.h"
#include "app/shell/kiosk/attract_screen.h"
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
  std::printf("bundled attract journal at grid %d: %zu clouds kept (%zu dropped), %zu bytes\n",
              kGrid, replay.cloudsKept(), replay.cloudsDropped(), replay.keyframeBytes());
  EXPECT_EQ(replay.cloudsDropped(), 0u) << "the bundled journal fits the default budget";
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

// A journal of `strokes` short strokes in rows across a 640×360 screen, each on sky no stroke
// before it covered, so the cloud grows with every one (the case where a copy per stroke costs
// the most).
std::vector<JournalRecord> longAttractJournal(int strokes) {
  constexpr int kW = 640, kH = 360;
  PaintSessionSettings settings;
  settings.screen_width = kW;
  settings.screen_height = kH;
  settings.grid = 64;
  PaintSession recorder(settings, BrushConfig{}, MappingConfig{});
  recorder.setQuietMapping(true);
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("cb_long_attract_" + std::to_string(::getpid()) + ".cbj"))
                               .string();
  JournalWriter journal;
  EXPECT_TRUE(journal.open(path)) << journal.error();
  const PenDeviceInfo tablet = syntheticTablet(kW, kH);
  recorder.setDevice(tablet, 0);
  recorder.recordTo(&journal, 0);
  int64_t t = 1'000'000'000;
  for (int i = 0; i < strokes; ++i) {
    const float x = 40.0f + float(i % 8) * 72.0f, y = 60.0f + float((i / 8) % 6) * 48.0f;
    SyntheticStroke s;
    s.control_points = {{x, y}, {x + 24.0f, y - 10.0f}, {x + 48.0f, y}};
    s.speed_px_s = 600.0f;
    const std::vector<PenSample> samples = syntheticPenSamples(s, tablet, kW, kH, 200.0, t);
    for (const PenSample& sample : samples) recorder.feed(sample);
    t = samples.back().t_ns + 500'000'000;
  }
  recorder.recordTo(nullptr, t);
  journal.close();
  JournalReadResult read = readJournal(path);
  std::filesystem::remove(path);
  EXPECT_TRUE(read.error.empty()) << read.error;
  return std::move(read.records);
}

struct LongReplayFigures {
  size_t strokes = 0, peak = 0, held = 0, empty = 0, newest = 0, every_copy = 0, kept = 0;
  size_t dropped = 0;
};

// Replays `records` with `budget` and checks the keyframes: the final cloud is the journal's,
// and every cloud kept is one the journal made, in the journal's order.
LongReplayFigures replayLong(const std::vector<JournalRecord>& records, size_t budget) {
  const RecordedSettings recorded = recordedSettings(records, BrushConfig{}, MappingConfig{});
  // The clouds after each stroke, as applied here in order, and what keeping a copy of each (as
  // the keyframes did before the budget) would hold.
  PaintSession direct(recorded.settings, recorded.brush, recorded.mapping);
  direct.setQuietMapping(true);
  LongReplayFigures f;
  f.empty = f.every_copy = direct.volume().memoryBytes();
  // Records applied, checksum: the empty sky, then the cloud after each stroke.
  std::vector<std::pair<size_t, uint64_t>> clouds = {{0, volumeChecksum(direct.volume())}};
  uint64_t generation = direct.volume().generation();
  for (size_t i = 0; i < records.size(); ++i) {
    std::string error;
    if (records[i].type != JournalRecordType::kSession) {
      EXPECT_TRUE(direct.applyRecord(records[i], nullptr, &error)) << i << ": " << error;
    }
    if (direct.volume().generation() != generation) {
      generation = direct.volume().generation();
      clouds.emplace_back(i + 1, volumeChecksum(direct.volume()));
      f.every_copy += direct.volume().memoryBytes();
    }
  }
  f.strokes = clouds.size() - 1;
  f.newest = direct.volume().memoryBytes();
  AttractReplay replay(records, recorded.settings, recorded.brush, recorded.mapping, Light{},
                       budget);
  replay.waitUntilFinished();
  EXPECT_TRUE(replay.problems().empty());
  f.peak = replay.peakKeyframeBytes();
  f.held = replay.keyframeBytes();
  f.kept = replay.cloudsKept();
  f.dropped = replay.cloudsDropped();
  EXPECT_EQ(volumeChecksum(*replay.keyframeAt(records.size()).volume),
            volumeChecksum(direct.volume()))
      << "the newest cloud is never dropped";
  // Walking the keyframes by records, each cloud shown is one the journal made (the empty sky
  // or the cloud after some stroke), never one from before the previous cloud shown.
  size_t at = 0;
  for (const auto& [applied, checksum] : clouds) {
    (void)checksum;
    const uint64_t shown = volumeChecksum(*replay.keyframeAt(applied).volume);
    size_t found = at;
    while (found < clouds.size() && clouds[found].second != shown) ++found;
    EXPECT_LT(found, clouds.size())
        << "the keyframe at record " << applied << " shows a cloud the journal never made";
    if (found < clouds.size()) {
      EXPECT_LE(clouds[found].first, applied) << "a stroke shown before it was painted";
      at = found;
    }
  }
  return f;
}

TEST(AttractReplay, ALongJournalsKeyframesStayWithinTheBudget) {
  // Sizes: 24 and 96 strokes (a long journal is four times as long). The budget is a quarter of
  // what a copy per stroke of the short journal holds, so it is in play for both.
  const std::vector<JournalRecord> short_journal = longAttractJournal(24);
  const std::vector<JournalRecord> long_journal = longAttractJournal(96);
  const LongReplayFigures probe = replayLong(short_journal, size_t(1) << 40);
  ASSERT_EQ(probe.strokes, 24u);
  EXPECT_EQ(probe.dropped, 0u) << "under a budget it never reaches, every cloud stays";
  EXPECT_EQ(probe.peak, probe.every_copy) << "the keyframes held one copy per stroke";
  const size_t budget = probe.every_copy / 4;
  const LongReplayFigures a = replayLong(short_journal, budget);
  const LongReplayFigures b = replayLong(long_journal, budget);
  ASSERT_EQ(b.strokes, 96u);
  std::printf(
      "attract keyframe bytes (budget %zu): %zu strokes: peak %zu, held %zu, newest cloud %zu, "
      "a copy per stroke %zu, clouds kept %zu dropped %zu; %zu strokes: peak %zu, held %zu, "
      "newest cloud %zu, a copy per stroke %zu, clouds kept %zu dropped %zu\n",
      budget, a.strokes, a.peak, a.held, a.newest, a.every_copy, a.kept, a.dropped, b.strokes,
      b.peak, b.held, b.newest, b.every_copy, b.kept, b.dropped);
  // The bound: the budget plus the newest cloud (counted as it arrives, before the thinning),
  // whatever the journal's length; after the thinning, the budget or the empty sky and the
  // newest cloud alone.
  for (const LongReplayFigures& f : {a, b}) {
    EXPECT_LE(f.peak, budget + f.newest);
    EXPECT_LE(f.held, std::max(budget, f.empty + f.newest));
    EXPECT_GT(f.dropped, 0u);
    EXPECT_GE(f.kept, 3u) << "the budget still holds some steps of the painting";
  }
  EXPECT_GT(b.every_copy, 8 * budget) << "a copy per stroke grows with the square of the length";
}

}  // namespace
}  // namespace cb
