// Every presented frame's timing journalled as a Frame record (drivers/core/journal_frame.h):
// the codec, the statistics `replay --stats` prints, and the painter on the frame loop with a
// replayed pen on its real time line — each sample attributed to exactly one frame, in order,
// times monotonic, the lift frame flagged — and the journal replaying to the same volume.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>

#include "app/session/paint_session.h"
#include "app/session/session_replay.h"
#include "app/session/synthetic_session.h"
#include "app/shell/painter/paint_loop.h"
#include "app/study/frame_timing_stats.h"
#include "drivers/core/journal.h"
#include "drivers/core/journal_frame.h"
#include "drivers/replay/replay_pen_source.h"
#include "tests/support/recorded_painter.h"
#include "tests/support/test_display.h"

namespace cb {
namespace {

constexpr int kW = 320, kH = 180, kGrid = 64;

TEST(FrameRecord, RoundTripsAtMicrosecondResolution) {
  FrameRecord r;
  r.frame = 41;
  r.source = PresentSource::kFlipEvent;
  r.missed_refresh = true;
  r.lift = true;
  r.new_samples = 3;
  r.present_ns = 5'000'000'000;
  r.newest_sample_ns = r.present_ns - 7'250'000;
  r.oldest_sample_ns = r.present_ns - 17'250'000;
  r.begin_ns = r.present_ns - 12'000'000;
  r.ready_ns = r.present_ns - 1'000'000;
  r.cpu_us = 9000;
  r.refresh_us = 16667;
  r.skipped_refreshes = 2;
  const std::vector<uint8_t> payload = encodeFrameRecord(r);
  ASSERT_EQ(payload.size(), kFrameRecordBytes);
  const std::optional<FrameRecord> back = decodeFrameRecord(r.present_ns, payload);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->frame, 41u);
  EXPECT_EQ(back->source, PresentSource::kFlipEvent);
  EXPECT_TRUE(back->missed_refresh);
  EXPECT_FALSE(back->nominal_refresh);
  EXPECT_TRUE(back->lift);
  EXPECT_EQ(back->new_samples, 3u);
  EXPECT_EQ(back->newest_sample_ns, r.newest_sample_ns);
  EXPECT_EQ(back->oldest_sample_ns, r.oldest_sample_ns);
  EXPECT_EQ(back->begin_ns, r.begin_ns);
  EXPECT_EQ(back->ready_ns, r.ready_ns);
  EXPECT_EQ(back->skipped_refreshes, 2u);
  // A frame showing no new sample keeps "none", not a time.
  FrameRecord idle;
  idle.present_ns = 1'000'000;
  EXPECT_EQ(decodeFrameRecord(idle.present_ns, encodeFrameRecord(idle))->newest_sample_ns, 0);
  std::vector<uint8_t> short_payload(payload.begin(), payload.end() - 1);
  EXPECT_FALSE(decodeFrameRecord(0, short_payload));
}

TEST(FrameTimingStats, PercentilesLiftsAndMissedRefreshes) {
  // 100 consecutive ink frames 10 ms apart, sample -> present 1..100 ms; one lift frame of
  // 300 ms; two late frames in the last quarter.
  std::vector<FrameRecord> frames;
  for (uint32_t i = 0; i < 101; ++i) {
    FrameRecord f;
    f.frame = i;
    f.present_ns = 1'000'000'000 + int64_t(i) * 10'000'000;
    f.ready_ns = f.present_ns - 500'000;
    f.new_samples = 1;
    const int64_t latency_ms = i < 100 ? i + 1 : 300;
    f.newest_sample_ns = f.oldest_sample_ns = f.present_ns - latency_ms * 1'000'000;
    f.lift = i == 100;
    f.missed_refresh = i == 90 || i == 95;
    f.skipped_refreshes = f.missed_refresh ? 1 : 0;
    frames.push_back(f);
  }
  // A frame showing a sample stamped on another clock (no time kept): counted, no latency.
  FrameRecord untimed = frames.back();
  untimed.frame = 101;
  untimed.lift = false;
  untimed.missed_refresh = false;
  untimed.newest_sample_ns = untimed.oldest_sample_ns = 0;
  frames.push_back(untimed);
  const FrameTimingStats s = frameTimingStats(frames);
  EXPECT_EQ(s.frames, 102u);
  EXPECT_EQ(s.untimed_frames, 1u);
  EXPECT_EQ(s.ink_frames, 100u);
  EXPECT_DOUBLE_EQ(s.sample_to_present.p50, 50.0);
  EXPECT_DOUBLE_EQ(s.sample_to_present.p95, 95.0);
  EXPECT_DOUBLE_EQ(s.sample_to_present.p99, 99.0);
  EXPECT_DOUBLE_EQ(s.sample_to_ready.p50, 49.5);
  EXPECT_EQ(s.lift_to_present.n, 1u);
  EXPECT_DOUBLE_EQ(s.lift_to_present.max, 300.0);
  EXPECT_DOUBLE_EQ(s.interval.p50, 10.0);
  EXPECT_EQ(s.missed_frames, 2u);
  EXPECT_EQ(s.skipped_refreshes, 2u);
  EXPECT_EQ(s.quarters[3].missed_frames, 2u);
  EXPECT_EQ(s.quarters[0].missed_frames, 0u);
  EXPECT_LT(s.quarters[0].sample_to_present.p50, s.quarters[3].sample_to_present.p50);
  size_t binned = 0;
  for (size_t n : s.histogram) binned += n;
  EXPECT_EQ(binned, 100u);
  EXPECT_EQ(s.histogram.front(), 3u);  // 1, 2, 3 ms below the first edge (4 ms)
  const std::string text = formatFrameTimingStats(s, "");
  EXPECT_NE(text.find("p95 95.0"), std::string::npos) << text;
  EXPECT_NE(formatFrameTimingStats(frameTimingStats({}), "").find("no Frame records"),
            std::string::npos);
}

// The painter's loop with the pen on its real time line: `ink_first` on (late latching) or off.
void paintAndCheck(bool ink_first) {
  const std::string dir =
      (std::filesystem::temp_directory_path() /
       ("cb_frame_timing_" + std::to_string(::getpid()) + (ink_first ? "_ink" : "_base")))
          .string();
  std::filesystem::create_directories(dir + "/state");
  const PenDeviceInfo tablet = syntheticTablet(kW, kH);
  const std::string pen_path = dir + "/pen.cbj";
  size_t pen_samples = 0;
  {
    JournalWriter journal;
    ASSERT_TRUE(journal.open(pen_path));
    const auto info = encodeDeviceInfo(tablet);
    journal.append(JournalRecordType::kDevice, 0, info.data(), info.size());
    for (const PenSample& s : syntheticPenSamples(referencePaintStrokes(kW, kH)[0], tablet, kW, kH,
                                                  200.0, 1'000'000'000)) {
      journal.appendPenSample(s);
      ++pen_samples;
    }
  }
  std::string error;
  test::RecordedPainter painter;
  ASSERT_TRUE(painter.open({kW, kH, kGrid}, BrushConfig{}, MappingConfig{}, dir + "/session.cbj",
                           MonotonicClock().nowNs(), &error))
      << error;
  Display& display = *painter.display;
  PaintSession& session = *painter.session;
  PaintLoopOptions options;
  options.max_seconds = 60.0;  // a bound for a stuck loop; the replay ends it in about 2 s
  options.ink_first = ink_first;
  options.state_dir = dir + "/state";
  options.config_dir = dir + "/config";
  ReplayOptions replay;
  replay.realtime = true;
  replay.restamp = true;
  ReplayPenSource pen(pen_path, replay);
  PaintLoop loop(display, painter.renderer, session.volume(), Light{}, options);
  loop.attachPen(&pen, &session);
  PaintLoopSummary summary;
  ASSERT_TRUE(loop.run(nullptr, &summary, &error)) << error;
  EXPECT_EQ(summary.quit_reason, "replay finished");
  painter.journal.close();

  const JournalReadResult read = readJournal(painter.recorded);
  ASSERT_TRUE(read.error.empty()) << read.error;
  std::vector<FrameRecord> frames;
  std::vector<PenSample> samples;
  for (const JournalRecord& r : read.records) {
    if (r.type == JournalRecordType::kPenSample) samples.push_back(*decodePenSample(r.payload));
    if (r.type != JournalRecordType::kFrame) continue;
    const std::optional<FrameRecord> f = decodeFrameRecord(r.t_ns, r.payload);
    ASSERT_TRUE(f);
    frames.push_back(*f);
  }
  ASSERT_EQ(samples.size(), pen_samples);
  ASSERT_EQ(long(frames.size()), summary.frames) << "one Frame record per presented frame";
  size_t attributed = 0, lifts = 0, next_sample = 0;
  for (size_t i = 0; i < frames.size(); ++i) {
    const FrameRecord& f = frames[i];
    EXPECT_EQ(f.frame, uint32_t(i));
    EXPECT_EQ(f.source, PresentSource::kFinish);  // the test display is surfaceless
    EXPECT_LE(f.begin_ns, f.ready_ns);
    EXPECT_LE(f.ready_ns, f.present_ns);
    if (i > 0) {
      EXPECT_GT(f.present_ns, frames[i - 1].present_ns);
    }
    if (f.lift) ++lifts;
    if (!f.hasSample()) continue;
    // The frame first shows the next samples of the pen, in order: the oldest and newest it
    // names are the first and last of them (microsecond resolution).
    ASSERT_LE(next_sample + f.new_samples, samples.size());
    EXPECT_NEAR(double(f.oldest_sample_ns), double(samples[next_sample].t_ns), 1000.0);
    EXPECT_NEAR(double(f.newest_sample_ns), double(samples[next_sample + f.new_samples - 1].t_ns),
                1000.0);
    EXPECT_LE(f.newest_sample_ns, f.present_ns);
    next_sample += f.new_samples;
    attributed += f.new_samples;
  }
  // Every sample up to the last that changed the picture is shown by exactly one frame; the
  // samples of the loop's last iteration (the pen leaving, read as the replay ended) may go
  // unpresented, never a sample with the tip down.
  EXPECT_GT(attributed, pen_samples / 2);
  for (size_t i = attributed; i < samples.size(); ++i)
    EXPECT_FALSE(samples[i].tipDown()) << "sample " << i << " of " << samples.size();
  EXPECT_EQ(lifts, 1u) << "the one stroke's cloud is shown by one lift frame";
  EXPECT_EQ(summary.lift_sample_to_lit_ms.size(), 1u) << "pen-up timed from the lift sample";

  // The Frame records change nothing a replay makes.
  const SessionReplay again = replaySession(read, BrushConfig{}, MappingConfig{});
  EXPECT_TRUE(again.complete());
  EXPECT_EQ(volumeChecksum(again.session->volume()), volumeChecksum(session.volume()));
  std::filesystem::remove_all(dir);
}

TEST(FrameTiming, EveryPresentedFrameIsJournalledWithTheSamplesItShows) {
  paintAndCheck(true);
}
TEST(FrameTiming, TheLoopWithoutLateLatchingToo) {
  paintAndCheck(false);
}

}  // namespace
}  // namespace cb
