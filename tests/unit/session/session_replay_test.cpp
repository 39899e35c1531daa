// A session recorded from the committed synthetic strokes replays to a byte-identical volume on
// 1, 2 and 8 threads and across runs; a torn journal replays its intact prefix and says where it
// broke.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "app/core/parallel_for.h"
#include "app/session/paint_session.h"
#include "app/session/session_replay.h"
#include "app/session/synthetic_session.h"

namespace cb {
namespace {

constexpr int kScreenW = 320, kScreenH = 180, kGrid = 64;

struct Recording {
  std::string path;
  uint64_t checksum = 0;
  uint32_t strokes = 0;
  std::vector<int64_t> lift_times;  // t_ns of the sample that ended each stroke
};

BrushConfig testBrush() {
  BrushConfig brush;
  brush.default_brush = BrushKind::k3D;
  return brush;
}

// Paints the reference strokes through a recording PaintSession, the second one from an orbited
// camera with the 2D brush, so the journal carries UI changes that matter.
Recording record(const std::string& path) {
  Recording rec;
  rec.path = path;
  PaintSessionSettings settings;
  settings.screen_width = kScreenW;
  settings.screen_height = kScreenH;
  settings.grid = kGrid;
  PaintSession session(settings, testBrush(), MappingConfig{});
  session.setQuietMapping(true);
  JournalWriter journal;
  EXPECT_TRUE(journal.open(path)) << journal.error();
  session.recordTo(&journal, 0);
  const PenDeviceInfo tablet = syntheticTablet(kScreenW, kScreenH);
  session.setDevice(tablet, 0);
  const std::vector<SyntheticStroke> strokes = referencePaintStrokes(kScreenW, kScreenH);
  int64_t t0 = 1'000'000'000;
  std::string error;
  for (size_t i = 0; i < strokes.size(); ++i) {
    if (i == 1) {
      EXPECT_TRUE(session.apply(ui::SetCamera{Camera::reference().orbited(20.0f)}, t0, &error))
          << error;
      EXPECT_TRUE(session.apply(ui::SetBrush{BrushKind::k2D}, t0, &error)) << error;
    }
    for (const PenSample& s :
         syntheticPenSamples(strokes[i], tablet, kScreenW, kScreenH, 200.0, t0)) {
      const SampleOutcome out = session.feed(s);
      if (out.stroke_mapped) rec.lift_times.push_back(s.t_ns);
      t0 = s.t_ns;
    }
    t0 += 500'000'000;
  }
  journal.close();
  rec.strokes = session.strokesMapped();
  rec.checksum = volumeChecksum(session.volume());
  return rec;
}

SessionReplay replayFile(const std::string& path) {
  return replaySession(readJournal(path), testBrush(), MappingConfig{});
}

std::string tempPath(const char* name) {
  return (std::filesystem::temp_directory_path() /
          (std::string("cb_session_replay_") + std::to_string(::getpid()) + "_" + name))
      .string();
}

TEST(SessionReplay, BadUiChangesAreRejectedWithTheirName) {
  PaintSession session({kScreenW, kScreenH, kGrid}, testBrush(), MappingConfig{});
  std::string error;
  UiChange change;
  EXPECT_FALSE(parseUiChange(JournalRecordType::kUi, "brush=oil", &change, &error));
  EXPECT_NE(error.find("oil"), std::string::npos) << error;
  EXPECT_FALSE(parseUiChange(JournalRecordType::kUi, "zoom=2", &change, &error));
  EXPECT_NE(error.find("zoom"), std::string::npos) << error;
  EXPECT_FALSE(parseUiChange(JournalRecordType::kUi, "camera_orbit=x", &change, &error));
  EXPECT_FALSE(session.apply(ui::Undo{}, 0, &error)) << "nothing to undo yet";
  EXPECT_NE(error.find("nothing to undo"), std::string::npos) << error;
  PaintSessionSettings parsed;
  EXPECT_FALSE(parseSessionSettings("grid = 4\n", &parsed, &error));
  EXPECT_NE(error.find("line 1"), std::string::npos) << error;
}

TEST(SessionReplay, SameVolumeOnAnyThreadCountAndAcrossRuns) {
  setWorkerThreads(2);
  const Recording rec = record(tempPath("full.cbj"));
  ASSERT_EQ(rec.strokes, 2u) << "both reference strokes should have been lifted and mapped";

  std::vector<uint64_t> sums;
  for (int threads : {1, 2, 8, 1}) {
    setWorkerThreads(threads);
    const SessionReplay replay = replayFile(rec.path);
    ASSERT_TRUE(replay.session);
    EXPECT_TRUE(replay.complete())
        << replay.journal_error << (replay.problems.empty() ? "" : replay.problems[0]);
    EXPECT_EQ(replay.strokes_mapped, 2u);
    // The paint view of the second stroke came from the journal, not from the default.
    EXPECT_EQ(replay.session->camera().eye, Camera::reference().orbited(20.0f).eye);
    sums.push_back(volumeChecksum(replay.session->volume()));
    EXPECT_EQ(sums.back(), rec.checksum) << "replay on " << threads << " threads";
  }
  // The volume holds a cloud (an empty volume would also replay identically).
  const SessionReplay replay = replayFile(rec.path);
  const Volume& v = replay.session->volume();
  double sum = 0.0;
  for (float d : v.toDense()) sum += d;
  EXPECT_GT(sum, 1.0);
  setWorkerThreads(0);
  std::filesystem::remove(rec.path);
}

TEST(SessionReplay, TornJournalReplaysItsIntactPrefixAndSaysWhere) {
  setWorkerThreads(2);
  const Recording rec = record(tempPath("torn_src.cbj"));
  ASSERT_EQ(rec.lift_times.size(), 2u);
  std::ifstream in(rec.path, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
  // Cut inside a pen-sample record of the second stroke, keeping the first stroke's lift.
  const JournalReadResult full = readJournal(rec.path);
  size_t offset = 16, cut = 0;  // header: magic, version, flags
  for (const JournalRecord& r : full.records) {
    // File version 2 framing: marker, type, length, t_ns, payload, CRC (JOURNAL.md section 1).
    const size_t size = 4 + 4 + 4 + 8 + r.payload.size() + 4;
    if (r.type == JournalRecordType::kPenSample && r.t_ns > rec.lift_times[0] + 600'000'000) {
      cut = offset + size / 2;
      break;
    }
    offset += size;
  }
  ASSERT_GT(cut, 0u);
  const std::string torn = tempPath("torn.cbj");
  std::ofstream(torn, std::ios::binary).write(bytes.data(), std::streamsize(cut));

  const SessionReplay replay = replayFile(torn);
  ASSERT_TRUE(replay.session);
  EXPECT_FALSE(replay.complete());
  EXPECT_NE(replay.journal_error.find("byte " + std::to_string(offset)), std::string::npos)
      << replay.journal_error;
  EXPECT_EQ(replay.strokes_mapped, 1u) << "the first stroke is intact and must be mapped";
  EXPECT_NE(volumeChecksum(replay.session->volume()), rec.checksum);

  // The prefix leaves the volume as it was right after the first stroke was mapped.
  JournalReadResult first_stroke;
  for (const JournalRecord& r : full.records)
    if (r.t_ns <= rec.lift_times[0]) first_stroke.records.push_back(r);
  const SessionReplay reference = replaySession(first_stroke, testBrush(), MappingConfig{});
  EXPECT_EQ(reference.strokes_mapped, 1u);
  EXPECT_EQ(volumeChecksum(replay.session->volume()), volumeChecksum(reference.session->volume()));
  setWorkerThreads(0);
  std::filesystem::remove(rec.path);
  std::filesystem::remove(torn);
}

// Journals recorded by main at 9e22266 (before spheres.outline_chord_voxels,
// edges.tangent_at_sphere_depth and stroke.auto_end_light_by_hysteresis; their brush texts still
// carry stroke.down_pressure/up_pressure) replay to the volume that version made: keys their
// recorded texts lack take the values of app/session/recorded_settings.h, not today's defaults.
// Where the files come from: tests/unit/session/README.md.
TEST(SessionReplay, JournalsFrom9e22266ReplayToTheirOldChecksums) {
  setWorkerThreads(2);
  const std::string dir = std::string(CB_SOURCE_DIR) + "/tests/unit/session/";
  const struct {
    const char* file;
    uint64_t checksum;  // printed by `cloudbrush replay FILE` built at 9e22266
  } journals[] = {{"attract_9e22266.cbj", 0xafd262bae80f2025ull},
                  {"attract_painted_at_grid256.cbj", 0xae66946f7e893a52ull}};
  for (const auto& j : journals) {
    SCOPED_TRACE(j.file);
    const SessionReplay replay = replayFile(dir + j.file);
    ASSERT_TRUE(replay.session);
    EXPECT_TRUE(replay.recorded_settings);
    EXPECT_TRUE(replay.complete())
        << replay.journal_error << (replay.problems.empty() ? "" : replay.problems[0]);
    EXPECT_EQ(replay.strokes_mapped, 5u);
    const MappingConfig& m = replay.session->mappingConfig();
    EXPECT_EQ(m.spheres.outline_chord_voxels, 0.0f);
    EXPECT_FALSE(m.edges.tangent_at_sphere_depth);
    EXPECT_FALSE(replay.session->brushConfig().stroke.auto_end_light_by_hysteresis);
    // Keys of specification 1.6: painted at size 1, no billows, the skeleton once a step.
    EXPECT_EQ(replay.session->brushSize(), 1.0f);
    EXPECT_EQ(replay.session->brushConfig().skeleton.stamp_spacing_px, 0.0f);
    EXPECT_EQ(m.spheres.billow_amplitude, 0.0f);
    EXPECT_EQ(volumeChecksum(replay.session->volume()), j.checksum);
  }
  // A local config lacking those keys gets today's defaults, not the recorded texts' values.
  const MappingConfig local = parseMappingConfigText("[spheres]\ndensity = 1.0\n", "local");
  EXPECT_EQ(local.spheres.outline_chord_voxels, MappingConfig{}.spheres.outline_chord_voxels);
  EXPECT_TRUE(local.edges.tangent_at_sphere_depth);
  setWorkerThreads(0);
}

}  // namespace
}  // namespace cb
