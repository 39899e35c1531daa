// The session's record: the journal is on the disk at every stroke end, a session
// resumes from its journal, replays with the settings in force (whatever the local config),
// keeps each stroke's mapping time and marks task and stroke boundaries for other recorders.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <chrono>
#include <thread>

#include "app/session/paint_session.h"
#include "app/session/session_replay.h"
#include "app/session/session_resume.h"
#include "app/session/sync_marker_sender.h"
#include "app/session/synthetic_session.h"
#include "app/study/session_trace.h"
#include "app/study/stroke_table.h"
#include "drivers/core/journal_records.h"

namespace cb {
namespace {

constexpr int kScreenW = 320, kScreenH = 180, kGrid = 48;

PaintSessionSettings testSettings() {
  PaintSessionSettings settings;
  settings.screen_width = kScreenW;
  settings.screen_height = kScreenH;
  settings.grid = kGrid;
  return settings;
}

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("cb_session_record_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

// The raw samples of the reference strokes, half a second apart.
std::vector<PenSample> referenceSamples() {
  const PenDeviceInfo tablet = syntheticTablet(kScreenW, kScreenH);
  std::vector<PenSample> samples;
  int64_t t0 = 1'000'000'000;
  for (const SyntheticStroke& stroke : referencePaintStrokes(kScreenW, kScreenH)) {
    for (const PenSample& s : syntheticPenSamples(stroke, tablet, kScreenW, kScreenH, 200.0, t0)) {
      samples.push_back(s);
      t0 = s.t_ns;
    }
    t0 += 500'000'000;
  }
  return samples;
}

TEST(SessionRecord, TheJournalIsSyncedAtEveryStrokeEnd) {
  const std::string path = tempPath("sync.cbj");
  PaintSession session(testSettings(), BrushConfig{}, MappingConfig{});
  session.setQuietMapping(true);
  JournalWriter journal;
  ASSERT_TRUE(journal.open(path)) << journal.error();
  session.recordTo(&journal, 0);
  session.setDevice(syntheticTablet(kScreenW, kScreenH), 0);
  uint64_t syncs = journal.syncCount();
  int strokes = 0;
  for (const PenSample& s : referenceSamples()) {
    const SampleOutcome out = session.feed(s);
    if (out.stroke_mapped) {
      ++strokes;
      EXPECT_EQ(journal.syncCount(), syncs + 1) << "stroke " << strokes;
      EXPECT_FALSE(journal.hasUnsyncedRecords());
      syncs = journal.syncCount();
    }
  }
  EXPECT_GE(strokes, 2);
  journal.close();
  std::filesystem::remove(path);
}

// A brush and mapping unlike the defaults, as a tuned local config would be.
BrushConfig tunedBrush() {
  BrushConfig brush;
  brush.brush3d.diameter_px = 37.5f;
  brush.brush3d.absorption = 9.25f;
  brush.dispersion.max_dispersion = 0.3f;
  return brush;
}
MappingConfig tunedMapping() {
  MappingConfig mapping;
  mapping.spheres.density = 0.65f;
  mapping.noise.seed = 4242;
  mapping.circles.initial_diameter_px = 96;
  return mapping;
}

struct Painted {
  uint64_t checksum = 0;
  uint32_t strokes = 0;
};

// Paints `samples` through a session recording into `path` (the whole of them, or up to `stop`).
Painted paint(const std::string& path, const std::vector<PenSample>& samples, size_t stop,
              const BrushConfig& brush = BrushConfig{},
              const MappingConfig& mapping = MappingConfig{}, SyncMarkerSender* sender = nullptr) {
  PaintSession session(testSettings(), brush, mapping);
  session.setQuietMapping(true);
  session.setSyncSender(sender);
  JournalWriter journal;
  EXPECT_TRUE(journal.open(path)) << journal.error();
  session.recordTo(&journal, 0);
  session.setDevice(syntheticTablet(kScreenW, kScreenH), 0);
  if (sender) session.markSync("task_begin", "Task 1: a cumulus", 1);
  for (size_t i = 0; i < stop && i < samples.size(); ++i) session.feed(samples[i]);
  if (sender) session.markSync("task_end", "Task 1: a cumulus", samples.back().t_ns + 1);
  return {volumeChecksum(session.volume()), session.strokesMapped()};
}

// Restarting on the same journal resumes the session; what the pen does next lands
// as if nothing had happened, even when the crash came in the middle of a stroke and tore the
// record being written.
TEST(SessionRecord, AResumedSessionEndsWithTheUninterruptedVolume) {
  const std::vector<PenSample> samples = referenceSamples();
  const Painted whole = paint(tempPath("whole.cbj"), samples, samples.size());
  ASSERT_GE(whole.strokes, 2u);
  for (const size_t crash : {samples.size() / 3, samples.size() * 2 / 3}) {
    SCOPED_TRACE("crash after sample " + std::to_string(crash));
    const std::string path = tempPath("resumed.cbj");
    paint(path, samples, crash);
    std::filesystem::resize_file(path, std::filesystem::file_size(path) - 9);  // a torn record
    JournalWriter journal;
    ResumedSession resumed;
    std::string error;
    ASSERT_TRUE(resumeOrStartSession(path, testSettings(), BrushConfig{}, MappingConfig{}, &journal,
                                     &resumed, &error))
        << error;
    ASSERT_TRUE(resumed.resumed);
    EXPECT_NE(resumed.warning.find("cut "), std::string::npos) << resumed.warning;
    PaintSession& session = *resumed.session;
    session.setQuietMapping(true);
    // The painter selects the pen again as it starts: not a change.
    const uint64_t records_before = readJournal(path).records.size();
    session.setDevice(syntheticTablet(kScreenW, kScreenH), 2);
    session.setCalibration(session.calibration(), 2);
    EXPECT_EQ(readJournal(path).records.size(), records_before);
    for (const PenSample& s : samples)
      if (s.t_ns > resumed.last_sample_ns) session.feed(s);
    EXPECT_EQ(volumeChecksum(session.volume()), whole.checksum);
    EXPECT_EQ(session.strokesMapped(), whole.strokes);
    journal.close();
    const SessionReplay replay = replaySession(readJournal(path), BrushConfig{}, MappingConfig{});
    EXPECT_TRUE(replay.complete()) << (replay.problems.empty() ? "" : replay.problems[0]);
    EXPECT_EQ(volumeChecksum(replay.session->volume()), whole.checksum);
  }
  // A journal from another screen is refused, and left as it was.
  const std::string path = tempPath("resumed.cbj");
  const auto size = std::filesystem::file_size(path);
  PaintSessionSettings other = testSettings();
  other.screen_width = 640;
  JournalWriter journal;
  ResumedSession resumed;
  std::string error;
  EXPECT_FALSE(resumeOrStartSession(path, other, BrushConfig{}, MappingConfig{}, &journal, &resumed,
                                    &error));
  EXPECT_NE(error.find("320x180"), std::string::npos) << error;
  EXPECT_EQ(std::filesystem::file_size(path), size);
  // Nor is a file that is not a session's journal overwritten: a pen recording, a text file.
  const std::string pen_only = tempPath("pen_only.cbj");
  {
    JournalWriter writer;
    ASSERT_TRUE(writer.open(pen_only));
    writer.appendPenSample(referenceSamples().front());
  }
  const std::string text = tempPath("notes.txt");
  std::ofstream(text) << "not a journal";
  for (const std::string& other_file : {pen_only, text}) {
    const auto before = std::filesystem::file_size(other_file);
    EXPECT_FALSE(resumeOrStartSession(other_file, testSettings(), BrushConfig{}, MappingConfig{},
                                      &journal, &resumed, &error));
    EXPECT_NE(error.find("not overwriting"), std::string::npos) << error;
    EXPECT_EQ(std::filesystem::file_size(other_file), before);
    std::filesystem::remove(other_file);
  }
  std::filesystem::remove(path);
  std::filesystem::remove(tempPath("whole.cbj"));
}

// The journal records the brush and mapping in force, so a replay on a machine whose
// config was tuned since gives the same volume; a journal without them replays with the local
// config, as before.
TEST(SessionRecord, ReplayUsesTheRecordedBrushAndMappingNotTheLocalOnes) {
  const std::vector<PenSample> samples = referenceSamples();
  const std::string path = tempPath("settings.cbj");
  const Painted painted = paint(path, samples, samples.size(), tunedBrush(), tunedMapping());
  const JournalReadResult journal = readJournal(path);
  int settings_records = 0;
  for (const JournalRecord& r : journal.records)
    if (r.type == JournalRecordType::kSettings) {
      std::string name, body, error;
      ASSERT_TRUE(parseSettingsRecord(r.text(), &name, &body, &error)) << error;
      EXPECT_TRUE(name == "brush.toml" || name == "mapping.toml") << name;
      ++settings_records;
    }
  EXPECT_EQ(settings_records, 2);
  const SessionReplay local_defaults = replaySession(journal, BrushConfig{}, MappingConfig{});
  EXPECT_TRUE(local_defaults.complete()) << local_defaults.problems.front();
  EXPECT_TRUE(local_defaults.recorded_settings);
  EXPECT_EQ(volumeChecksum(local_defaults.session->volume()), painted.checksum);
  EXPECT_EQ(local_defaults.session->brushConfig().brush3d.diameter_px, 37.5f);
  EXPECT_EQ(local_defaults.session->mappingConfig().noise.seed, 4242u);

  JournalReadResult old = journal;  // as journals were before Settings records
  std::erase_if(old.records,
                [](const JournalRecord& r) { return r.type == JournalRecordType::kSettings; });
  const SessionReplay as_before = replaySession(old, BrushConfig{}, MappingConfig{});
  EXPECT_FALSE(as_before.recorded_settings);
  EXPECT_NE(volumeChecksum(as_before.session->volume()), painted.checksum)
      << "the tuned brush and mapping change the volume";
  const SessionReplay with_tuned = replaySession(old, tunedBrush(), tunedMapping());
  EXPECT_EQ(volumeChecksum(with_tuned.session->volume()), painted.checksum);

  // Every field survives the text: format, parse, format gives the same text.
  std::vector<std::string> errors;
  BrushConfig parsed;
  ASSERT_TRUE(parseBrushConfigText(formatBrushConfig(tunedBrush()), "brush", &parsed, &errors));
  EXPECT_EQ(formatBrushConfig(parsed), formatBrushConfig(tunedBrush()));
  EXPECT_EQ(formatMappingConfig(parseMappingConfigText(formatMappingConfig(tunedMapping()), "m")),
            formatMappingConfig(tunedMapping()));
  std::filesystem::remove(path);
}

// Each stroke's mapping time is journalled (a measurement: replay ignores it) and the
// study's stroke table reads it.
TEST(SessionRecord, MappingTimeOfEachStrokeIsInTheJournalAndTheStrokeTable) {
  const std::vector<PenSample> samples = referenceSamples();
  const std::string path = tempPath("mapping_time.cbj");
  const Painted painted = paint(path, samples, samples.size());
  std::vector<StrokeMappedRecord> mapped;
  for (const JournalRecord& r : readJournal(path).records)
    if (r.type == JournalRecordType::kStrokeMapped) {
      const std::optional<StrokeMappedRecord> m = parseStrokeMapped(r.text());
      ASSERT_TRUE(m.has_value()) << r.text();
      mapped.push_back(*m);
    }
  ASSERT_EQ(mapped.size(), painted.strokes);
  for (size_t i = 0; i < mapped.size(); ++i) {
    EXPECT_EQ(mapped[i].stroke, i);
    EXPECT_GT(mapped[i].mapping_ms, 0.0);
  }
  const std::vector<StrokeMeasures> table = measureStrokes(loadSessionTrace(path));
  ASSERT_EQ(table.size(), mapped.size());
  for (size_t i = 0; i < table.size(); ++i) {
    ASSERT_TRUE(table[i].mapping_ms.has_value()) << "stroke " << i;
    EXPECT_DOUBLE_EQ(*table[i].mapping_ms, mapped[i].mapping_ms);
  }
  // Timing is not an input: the replay's volume is the painted one (its own times differ).
  const SessionReplay replay = replaySession(readJournal(path), BrushConfig{}, MappingConfig{});
  EXPECT_EQ(volumeChecksum(replay.session->volume()), painted.checksum);
  std::filesystem::remove(path);
}

// Task and stroke boundaries reach another recorder as UDP datagrams on localhost,
// and the journal holds the same markers.
TEST(SessionRecord, SyncMarkersArriveOverUdpAndAreJournalled) {
  const int receiver = ::socket(AF_INET, SOCK_DGRAM, 0);
  ASSERT_GE(receiver, 0);
  sockaddr_in at{};
  at.sin_family = AF_INET;
  at.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(receiver, reinterpret_cast<sockaddr*>(&at), sizeof at), 0);
  socklen_t len = sizeof at;
  ASSERT_EQ(::getsockname(receiver, reinterpret_cast<sockaddr*>(&at), &len), 0);
  const int port = ntohs(at.sin_port);

  SyncMarkerSender sender;
  std::string error;
  EXPECT_FALSE(sender.open("127.0.0.1:99999", &error));
  EXPECT_NE(error.find("1..65535"), std::string::npos) << error;
  ASSERT_TRUE(sender.open("127.0.0.1:" + std::to_string(port), &error)) << error;
  const std::vector<PenSample> samples = referenceSamples();
  const std::string path = tempPath("sync.cbj");
  const Painted painted =
      paint(path, samples, samples.size(), BrushConfig{}, MappingConfig{}, &sender);
  std::vector<std::string> received;
  char buffer[2048];
  for (int tries = 0; tries < 200 && received.size() < sender.sent(); ++tries) {
    const ssize_t n = ::recv(receiver, buffer, sizeof buffer, MSG_DONTWAIT);
    if (n > 0)
      received.emplace_back(buffer, size_t(n));
    else
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ::close(receiver);
  std::vector<std::string> journalled;
  for (const JournalRecord& r : readJournal(path).records)
    if (r.type == JournalRecordType::kSync) journalled.emplace_back(r.text());
  EXPECT_EQ(received, journalled);
  ASSERT_EQ(received.size(), 2 + 2 * size_t(painted.strokes));
  std::vector<std::string> kinds;
  for (size_t i = 0; i < received.size(); ++i) {
    const std::optional<SyncMarker> m = parseSyncMarker(received[i]);
    ASSERT_TRUE(m.has_value()) << received[i];
    EXPECT_EQ(m->seq, i + 1);
    EXPECT_GT(m->wall_ns, int64_t(1'600'000'000) * 1'000'000'000);
    kinds.push_back(m->kind + " " + m->label);
  }
  EXPECT_EQ(kinds.front(), "task_begin Task 1: a cumulus");
  EXPECT_EQ(kinds[1], "stroke_begin 0");
  EXPECT_EQ(kinds[2], "stroke_end 0");
  EXPECT_EQ(kinds[3], "stroke_begin 1");
  EXPECT_EQ(kinds.back(), "task_end Task 1: a cumulus");
  EXPECT_EQ(sender.failed(), 0u);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace cb
