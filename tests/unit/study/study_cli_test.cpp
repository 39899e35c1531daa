// The real binary: `cloudbrush study export --volumes` on a recorded journal writes every file of
// its documented layout, and the exported volume is the replayed one (same checksum as
// `cloudbrush replay`); a manifest exported as 3 shards and merged gives the single run's files
// byte for byte; `study report` and `study export` refuse bad input naming file and field.
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>

#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include "app/session/session_replay.h"
#include "app/session/synthetic_session.h"
#include "app/volume/volume_file.h"
#include "drivers/core/journal.h"

#include "tests/support/command_run.h"
#include "tests/unit/study/sharded_export.h"

namespace cb {
namespace {

using test::CommandRun;

CommandRun run(const std::string& command) {
  return test::runCommand(command);
}

class StudyCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("cb_study_cli_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

// A painter-like journal: session, device, paint mode, 3D brush, the reference strokes.
void writeJournal(const std::string& path) {
  constexpr int kW = 1280, kH = 720;
  JournalWriter journal;
  ASSERT_TRUE(journal.open(path)) << journal.error();
  journal.append(JournalRecordType::kSession, 0,
                 "screen_width = 1280\nscreen_height = 720\ngrid = 48\nformat = 2\n");
  const PenDeviceInfo tablet = syntheticTablet(kW, kH);
  const std::vector<uint8_t> device = encodeDeviceInfo(tablet);
  journal.append(JournalRecordType::kDevice, 0, device.data(), device.size());
  journal.append(JournalRecordType::kMode, 0, "paint");
  journal.append(JournalRecordType::kUi, 0, "brush=3d");
  int64_t t = 1'000'000;
  for (const SyntheticStroke& stroke : referencePaintStrokes(kW, kH))
    for (const PenSample& s : syntheticPenSamples(stroke, tablet, kW, kH, 200.0, t)) {
      ASSERT_TRUE(journal.appendPenSample(s));
      t = s.t_ns + 5'000'000;
    }
}

TEST_F(StudyCli, ExportWritesEveryFileAndTheReplayedVolume) {
  const std::string journal = (dir_ / "p01-task1.cbj").string();
  writeJournal(journal);
  const std::string out = (dir_ / "export").string();
  const CommandRun exported = run(std::string(CB_CLOUDBRUSH_BIN) + " study export " + journal +
                                  " --out " + out + " --volumes --size 64x36");
  ASSERT_EQ(exported.status, 0) << exported.out;
  for (const char* file : {"traces.inkml", "samples.csv", "strokes.csv", "events.csv", "trials.csv",
                           "codebook.csv", "volumes/p01-task1.vdb", "volumes/p01-task1.cbvol",
                           "renders/p01-task1.exr", "renders/p01-task1.png"}) {
    EXPECT_TRUE(std::filesystem::exists(dir_ / "export" / file)) << file << "\n" << exported.out;
    EXPECT_NE(exported.out.find(file), std::string::npos) << "not reported: " << file;
  }
  const CommandRun replay =
      run(std::string(CB_CLOUDBRUSH_BIN) + " replay " + journal + " --threads 2");
  ASSERT_EQ(replay.status, 0) << replay.out;
  std::smatch match;
  ASSERT_TRUE(std::regex_search(replay.out, match, std::regex("volume checksum: ([0-9a-f]+)")));
  const Volume volume = loadVolume((dir_ / "export/volumes/p01-task1.cbvol").string());
  char checksum[32];
  std::snprintf(checksum, sizeof checksum, "%016" PRIx64, volumeChecksum(volume));
  EXPECT_EQ(checksum, match[1].str());
  size_t nonzero = 0;
  {
    const std::vector<float> volume_dense = volume.toDense();
    for (size_t i = 0; i < volume.voxelCount(); ++i) nonzero += volume_dense[i] != 0.0f;
  }
  ASSERT_GT(nonzero, 0u) << "the strokes left no cloud";
  openvdb::initialize();
  openvdb::io::File file((dir_ / "export/volumes/p01-task1.vdb").string());
  file.open();
  auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("density"));
  file.close();
  ASSERT_TRUE(grid);
  EXPECT_EQ(grid->activeVoxelCount(), openvdb::Index64(nonzero));
}

TEST_F(StudyCli, ReportOnTheThesisAnswers) {
  const std::string html_path = (dir_ / "report.html").string();
  const CommandRun report = run(std::string(CB_CLOUDBRUSH_BIN) + " study report " +
                                CB_STUDY_TEST_DIR + "/thesis_answers.csv --out " + html_path);
  ASSERT_EQ(report.status, 0) << report.out;
  std::ifstream in(html_path);
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("<td>0.265</td>"), std::string::npos);  // one-tailed p, Q3 vs Q6
  // Every construct of the bundled protocol; the thesis's answers have no lag item (Q28), so
  // that construct is NA and the page says why.
  EXPECT_NE(html.find("Constructs of the study protocol "), std::string::npos);
  EXPECT_NE(html.find("<td class=\"t\">Paint style</td><td class=\"t\">Q1 Q2 Q3 Q4 Q5 Q6</td>"
                      "<td>17</td>"),
            std::string::npos);
  EXPECT_NE(html.find("<td class=\"t\">Lag acceptance</td><td class=\"t\">Q28</td><td>0</td>"
                      "<td>NA</td>"),
            std::string::npos);
  EXPECT_NE(html.find("Lag acceptance: the answers have no Q28."), std::string::npos);
  EXPECT_NE(report.out.find("construct 'Lag acceptance': no item Q28"), std::string::npos)
      << report.out;
}

TEST_F(StudyCli, BadInputIsRefusedNamingFileAndField) {
  const std::string answers = (dir_ / "answers.csv").string();
  std::ofstream(answers) << "participant,Q1,Q2\nP1,5,7\n";
  const CommandRun report = run(std::string(CB_CLOUDBRUSH_BIN) + " study report " + answers +
                                " --out " + (dir_ / "r.html").string());
  EXPECT_EQ(report.status, 1);
  EXPECT_NE(report.out.find(answers + ": line 2, column 3: Q2: '7'"), std::string::npos)
      << report.out;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "r.html"));

  const std::string missing = (dir_ / "missing.cbj").string();
  const CommandRun exported = run(std::string(CB_CLOUDBRUSH_BIN) + " study export " + missing +
                                  " --out " + (dir_ / "x").string());
  EXPECT_EQ(exported.status, 1);
  EXPECT_NE(exported.out.find(missing), std::string::npos) << exported.out;

  const std::string not_journal = (dir_ / "notes.cbj").string();
  std::ofstream(not_journal) << "these are notes, not a journal\n";
  const CommandRun garbage = run(std::string(CB_CLOUDBRUSH_BIN) + " study export " + not_journal +
                                 " --out " + (dir_ / "y").string());
  EXPECT_EQ(garbage.status, 1);
  EXPECT_NE(garbage.out.find(not_journal + ": byte 0"), std::string::npos) << garbage.out;

  const CommandRun unknown = run(std::string(CB_CLOUDBRUSH_BIN) + " study frobnicate");
  EXPECT_EQ(unknown.status, 2);
  EXPECT_NE(unknown.out.find("unknown action 'frobnicate'"), std::string::npos) << unknown.out;
}

// Five sessions of a manifest as 3 shards (one run each, as a job array's tasks would), then
// the merge: the same files as one run over the whole manifest, byte for byte (.vdb by grid).
// A missing shard, a stale split and a mismatched manifest are refused, naming what.
TEST_F(StudyCli, AShardedExportMergesToTheSingleRunByteForByte) {
  const std::string manifest = test::writeShardedStudy(dir_, 5);
  const std::string bin = std::string(CB_CLOUDBRUSH_BIN) + " study export --manifest " + manifest;
  const std::string options = " --volumes --size 64x36";
  const CommandRun single = run(bin + " --out " + (dir_ / "single").string() + options);
  ASSERT_EQ(single.status, 0) << single.out;
  const std::string out = (dir_ / "sharded").string();
  const CommandRun early = run(bin + " --out " + out + " --shard 2/3" + options);
  ASSERT_EQ(early.status, 0) << early.out;
  const CommandRun incomplete = run(bin + " --out " + out + " --merge");
  EXPECT_EQ(incomplete.status, 1) << incomplete.out;
  EXPECT_NE(incomplete.out.find("shards/1-of-3/shard.txt: missing (shard 1 of 3 has not finished)"),
            std::string::npos)
      << incomplete.out;
  for (const char* shard : {"3/3", "1/3"}) {
    const CommandRun part = run(bin + " --out " + out + " --shard " + shard + options);
    ASSERT_EQ(part.status, 0) << shard << "\n" << part.out;
  }
  std::filesystem::create_directories(out + "/shards/1-of-2");
  const CommandRun stale = run(bin + " --out " + out + " --merge");
  EXPECT_EQ(stale.status, 1) << stale.out;
  EXPECT_NE(stale.out.find("shards of two splits"), std::string::npos) << stale.out;
  std::filesystem::remove_all(out + "/shards/1-of-2");
  // A manifest of other sessions: the shards' records name theirs.
  const std::string other = (dir_ / "other.txt").string();
  std::ofstream(other) << "P01-20261129T070001Z/session.cbj\nP02-20261129T070002Z/session.cbj\n";
  const CommandRun foreign = run(std::string(CB_CLOUDBRUSH_BIN) + " study export --manifest " +
                                 other + " --out " + out + " --merge");
  EXPECT_EQ(foreign.status, 1) << foreign.out;
  EXPECT_NE(foreign.out.find("its sessions are not this manifest's"), std::string::npos)
      << foreign.out;
  const CommandRun merged = run(bin + " --out " + out + " --merge");
  ASSERT_EQ(merged.status, 0) << merged.out;
  EXPECT_FALSE(std::filesystem::exists(out + "/shards")) << "the parts are removed once merged";
  test::expectSameExport(dir_ / "single", out);

  const CommandRun bad = run(bin + " --out " + out + " --shard 3/2");
  EXPECT_EQ(bad.status, 2) << bad.out;
  EXPECT_NE(bad.out.find("--shard: expected I/N"), std::string::npos) << bad.out;
  std::ofstream(manifest, std::ios::app) << "P09-20261129T070009Z/session.cbj\n";
  const CommandRun missing = run(bin + " --out " + out + " --shard 1/2");
  EXPECT_EQ(missing.status, 1) << missing.out;
  EXPECT_NE(missing.out.find(manifest + ":7: journal: '"), std::string::npos) << missing.out;
}

// A byte flipped in the middle of a journal: the export holds every sample around it, and
// exits 3 (as replay does) naming where the damage is.
TEST_F(StudyCli, ExportOfADamagedJournalKeepsEverythingAfterTheDamageAndExitsNonZero) {
  const std::string journal = (dir_ / "p02-task1.cbj").string();
  writeJournal(journal);
  const JournalReadResult clean = readJournal(journal);
  size_t samples = 0;
  for (const JournalRecord& r : clean.records) samples += r.type == JournalRecordType::kPenSample;
  {
    std::fstream f(journal, std::ios::in | std::ios::out | std::ios::binary);
    const auto middle = std::streamoff(std::filesystem::file_size(journal) / 2);
    f.seekg(middle);
    const char c = char(f.get());
    f.seekp(middle);
    f.put(char(c ^ 0x5a));
  }
  const CommandRun exported = run(std::string(CB_CLOUDBRUSH_BIN) + " study export " + journal +
                                  " --out " + (dir_ / "damaged").string());
  EXPECT_EQ(exported.status, 3) << exported.out;
  EXPECT_NE(exported.out.find("skipped 106 damaged bytes in 1 stretch"), std::string::npos)
      << exported.out;
  std::ifstream csv(dir_ / "damaged" / "samples.csv");
  size_t rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, 1 + samples - 1) << "every sample but the damaged one";
}

}  // namespace
}  // namespace cb
