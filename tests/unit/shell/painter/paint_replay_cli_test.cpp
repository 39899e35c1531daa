// End to end through the real binary: `cloudbrush paint --display surfaceless --backend replay`
// paints a recorded synthetic stroke and journals the session; `cloudbrush replay` of that journal
// reproduces the painted volume's checksum on 1 and 8 threads; a torn copy replays its intact
// part with exit status 3 and names the byte offset.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

#include "app/session/paint_session.h"
#include "app/session/synthetic_session.h"
#include "app/volume/scene_generators.h"
#include "app/volume/volume_file.h"

#include "tests/support/command_run.h"

namespace cb {
namespace {

using test::CommandRun;

CommandRun run(const std::string& command) {
  return test::runCommand(command);
}

std::string capture(const std::string& text, const std::string& pattern) {
  std::smatch match;
  return std::regex_search(text, match, std::regex(pattern)) ? match[1].str() : std::string();
}

// Records one synthetic stroke at 640x360 as the pen's input journal.
void recordPenJournal(const std::string& path, const SyntheticStroke& stroke) {
  PaintSession recorder({640, 360, 16}, BrushConfig{}, MappingConfig{});
  recorder.setQuietMapping(true);
  JournalWriter journal;
  ASSERT_TRUE(journal.open(path)) << journal.error();
  recorder.recordTo(&journal, 0);
  const PenDeviceInfo tablet = syntheticTablet(640, 360);
  recorder.setDevice(tablet, 0);
  for (const PenSample& s : syntheticPenSamples(stroke, tablet, 640, 360, 200.0, 1'000'000'000))
    recorder.feed(s);
}

TEST(PaintReplayCli, PaintedSessionReplaysToTheSameVolume) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("cb_paint_cli_" + std::to_string(::getpid())))
          .string();
  std::filesystem::create_directories(dir);
  // The pen's input: one synthetic stroke, recorded as a journal.
  const std::string pen_journal = dir + "/pen.cbj";
  ASSERT_NO_FATAL_FAILURE(recordPenJournal(pen_journal, pressureRamp(640, 360)));
  const std::string bin = CB_CLOUDBRUSH_BIN;
  const CommandRun paint =
      run("'" + bin + "' paint --display surfaceless --size 640x360 --grid 64 " +
          "--backend replay --journal '" + pen_journal + "' --session-dir '" + dir +
          "/sessions' --stats");
  ASSERT_EQ(paint.status, 0) << paint.out;
  EXPECT_NE(paint.out.find("(replay finished)"), std::string::npos) << paint.out;
  EXPECT_NE(paint.out.find("1 strokes mapped"), std::string::npos) << paint.out;
  const std::string session = capture(paint.out, "journal: (\\S+\\.cbj)");
  const std::string painted = capture(paint.out, "volume checksum ([0-9a-f]{16})");
  ASSERT_FALSE(session.empty()) << paint.out;
  ASSERT_FALSE(painted.empty()) << paint.out;
  std::printf("%s", paint.out.c_str());

  for (int threads : {1, 8}) {
    const CommandRun replay =
        run("'" + bin + "' replay '" + session + "' --threads " + std::to_string(threads));
    ASSERT_EQ(replay.status, 0) << replay.out;
    EXPECT_EQ(capture(replay.out, "volume checksum: ([0-9a-f]{16})"), painted)
        << "threads " << threads << "\n"
        << replay.out;
  }

  // Torn: drop the last 1000 bytes (inside the stroke's samples).
  std::ifstream in(session, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
  ASSERT_GT(bytes.size(), 2000u);
  const std::string torn = dir + "/torn.cbj";
  std::ofstream(torn, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size() - 1000));
  const CommandRun replay = run("'" + bin + "' replay '" + torn + "'");
  EXPECT_EQ(replay.status, 3) << replay.out;
  EXPECT_NE(replay.out.find("byte "), std::string::npos) << replay.out;
  EXPECT_NE(replay.out.find("intact records"), std::string::npos) << replay.out;

  const CommandRun missing = run("'" + bin + "' replay '" + dir + "/nothere.cbj'");
  EXPECT_EQ(missing.status, 1);
  EXPECT_NE(missing.out.find("nothere.cbj"), std::string::npos) << missing.out;
  std::filesystem::remove_all(dir);
}

// Keys B and N (pressed with --keys) are journalled; `cloudbrush replay` reproduces the
// painted volume, which differs from the same stroke painted without them.
TEST(PaintReplayCli, BrushAndMappingKeysReplayToTheSameVolume) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("cb_paint_keys_" + std::to_string(::getpid())))
          .string();
  std::filesystem::create_directories(dir);
  const std::string pen_journal = dir + "/pen.cbj";
  ASSERT_NO_FATAL_FAILURE(recordPenJournal(pen_journal, gentleCurve(640, 360)));
  const std::string bin = CB_CLOUDBRUSH_BIN;
  const auto paint = [&](const std::string& keys, const std::string& sessions) {
    return run("'" + bin + "' paint --display surfaceless --size 640x360 --grid 64 " +
               "--backend replay --journal '" + pen_journal + "' --session-dir '" + sessions + "'" +
               (keys.empty() ? "" : " --keys " + keys));
  };
  const CommandRun plain = paint("", dir + "/plain");
  const CommandRun keyed = paint("bn", dir + "/keyed");
  ASSERT_EQ(plain.status, 0) << plain.out;
  ASSERT_EQ(keyed.status, 0) << keyed.out;
  EXPECT_NE(keyed.out.find("method=ray-marching"), std::string::npos) << keyed.out;
  const std::string plain_sum = capture(plain.out, "volume checksum ([0-9a-f]{16})");
  const std::string keyed_sum = capture(keyed.out, "volume checksum ([0-9a-f]{16})");
  const std::string session = capture(keyed.out, "journal: (\\S+\\.cbj)");
  ASSERT_FALSE(plain_sum.empty() || keyed_sum.empty() || session.empty()) << keyed.out;
  EXPECT_NE(plain_sum, keyed_sum) << "the keys changed brush and mapping";
  const CommandRun replay = run("'" + bin + "' replay '" + session + "' --threads 2");
  ASSERT_EQ(replay.status, 0) << replay.out;
  EXPECT_EQ(capture(replay.out, "volume checksum: ([0-9a-f]{16})"), keyed_sum) << replay.out;

  // --open starts from a saved cloud: the painted volume holds it, and replay (which reads the
  // journal's "opened" marker) gives the same checksum.
  const std::string saved = dir + "/start.vol";
  {
    Volume start = makeBundledCumulus(glm::ivec3(64), 3);
    saveVolume(start, saved);
  }
  const CommandRun opened =
      run("'" + bin + "' paint --display surfaceless --size 640x360 --grid 64 " +
          "--backend replay --journal '" + pen_journal + "' --session-dir '" + dir +
          "/opened' --open '" + saved + "'");
  ASSERT_EQ(opened.status, 0) << opened.out;
  const std::string opened_sum = capture(opened.out, "volume checksum ([0-9a-f]{16})");
  EXPECT_NE(opened_sum, plain_sum) << "the stroke was painted over the opened cloud";
  const std::string opened_session = capture(opened.out, "journal: (\\S+\\.cbj)");
  const CommandRun opened_replay = run("'" + bin + "' replay '" + opened_session + "'");
  EXPECT_EQ(capture(opened_replay.out, "volume checksum: ([0-9a-f]{16})"), opened_sum)
      << opened_replay.out;
  const CommandRun wrong_grid =
      run("'" + bin + "' paint --display surfaceless --grid 32 " + "--backend replay --journal '" +
          pen_journal + "' --open '" + saved + "'");
  EXPECT_EQ(wrong_grid.status, 2);
  EXPECT_NE(wrong_grid.out.find("does not fit"), std::string::npos) << wrong_grid.out;

  const CommandRun bad = run("'" + bin + "' paint --display surfaceless --backend replay " +
                             "--journal '" + pen_journal + "' --keys b,f00");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.out.find("--keys: key 'f00'"), std::string::npos) << bad.out;
  std::filesystem::remove_all(dir);
}

// The journal carries the brush, mapping and render settings in force, so `cloudbrush
// replay` gives the same volume with a deliberately different local config; a journal without
// them (as before) does take the local config. --frames writes one PNG per frame.
TEST(PaintReplayCli, ReplayIgnoresADifferentLocalConfigAndWritesFrames) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("cb_replay_cfg_" + std::to_string(::getpid())))
          .string();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir + "/config");
  const std::string journal = dir + "/session.cbj";
  ASSERT_NO_FATAL_FAILURE(recordPenJournal(journal, gentleCurve(640, 360)));
  std::ofstream(dir + "/config/brush.toml") << "brush = \"2d\"\n[brush3d]\ndiameter_px = 30\n"
                                               "absorption = 5\n[brush2d]\nmax_diameter_px = 12\n";
  std::ofstream(dir + "/config/mapping.toml") << "[spheres]\ndensity = 0.5\n[noise]\nseed = 99\n";
  const std::string bin = CB_CLOUDBRUSH_BIN;
  const std::string tuned = "CLOUDBRUSH_CONFIG_DIR='" + dir + "/config' ";
  const CommandRun here = run("'" + bin + "' replay '" + journal + "'");
  const CommandRun there = run(tuned + "'" + bin + "' replay '" + journal + "'");
  ASSERT_EQ(here.status, 0) << here.out;
  ASSERT_EQ(there.status, 0) << there.out;
  const std::string sum = capture(here.out, "volume checksum: ([0-9a-f]{16})");
  ASSERT_FALSE(sum.empty()) << here.out;
  EXPECT_EQ(capture(there.out, "volume checksum: ([0-9a-f]{16})"), sum) << there.out;
  EXPECT_NE(there.out.find("as recorded in the journal"), std::string::npos) << there.out;

  // The same journal without its Settings records, as journals were before: the local config
  // decides, so the tuned one gives another volume.
  const std::string old = dir + "/old.cbj";
  {
    JournalWriter writer;
    ASSERT_TRUE(writer.open(old)) << writer.error();
    for (const JournalRecord& r : readJournal(journal).records)
      if (r.type != JournalRecordType::kSettings)
        writer.append(r.type, r.t_ns, r.payload.data(), r.payload.size());
  }
  const CommandRun old_here = run("'" + bin + "' replay '" + old + "'");
  const CommandRun old_there = run(tuned + "'" + bin + "' replay '" + old + "'");
  EXPECT_NE(old_there.out.find("from the local config"), std::string::npos) << old_there.out;
  EXPECT_NE(capture(old_there.out, "volume checksum: ([0-9a-f]{16})"),
            capture(old_here.out, "volume checksum: ([0-9a-f]{16})"))
      << "the tuned local config is read for a journal without recorded settings";

  // Frames: one PNG per 1/10 s of the pen's time line, the last showing the lit stroke.
  const CommandRun frames = run(tuned + "'" + bin + "' replay '" + journal + "' --frames '" + dir +
                                "/frames' --fps 10 --size 160x90");
  ASSERT_EQ(frames.status, 0) << frames.out;
  std::vector<int64_t> times;
  for (const JournalRecord& r : readJournal(journal).records)
    if (r.type == JournalRecordType::kPenSample) times.push_back(r.t_ns);
  ASSERT_FALSE(times.empty());
  const long expected = long((times.back() - times.front()) / 100'000'000) + 1;
  long pngs = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir + "/frames")) {
    std::ifstream png(entry.path(), std::ios::binary);
    char magic[4] = {};
    png.read(magic, 4);
    EXPECT_EQ(std::string(magic + 1, 3), "PNG") << entry.path();
    ++pngs;
  }
  EXPECT_EQ(pngs, expected);
  EXPECT_GT(pngs, 5);
  EXPECT_NE(frames.out.find("(100%)"), std::string::npos) << frames.out;
  EXPECT_EQ(capture(frames.out, "volume checksum: ([0-9a-f]{16})"), sum) << frames.out;
  char last[40];
  std::snprintf(last, sizeof last, "/frames/frame_%06ld.png", expected - 1);
  EXPECT_TRUE(std::filesystem::exists(dir + last));
  if (const char* keep = std::getenv("CB_KEEP_FRAMES"))
    std::filesystem::copy(dir + "/frames", std::string(keep) + "/replay_frames",
                          std::filesystem::copy_options::recursive |
                              std::filesystem::copy_options::overwrite_existing);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cb
