// A study export split over machines (app/study/export_shards.h): the shards' session blocks
// cover the manifest once, in order, with sizes differing by at most one (random sizes, seeded
// by CB_TEST_SEED); --shard and manifest lines are refused naming what and where; a shard's
// record reads back as written, and a torn or foreign one is refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "app/study/export_shards.h"
#include "tests/support/test_seed.h"

namespace cb {
namespace {

TEST(ExportShards, BlocksCoverEverySessionOnceInOrderAndDifferByAtMostOne) {
  std::mt19937 random(test::testSeed("ExportShards.Blocks"));
  for (int round = 0; round < 2000; ++round) {
    const size_t sessions = std::uniform_int_distribution<size_t>(0, 500)(random);
    const int count = std::uniform_int_distribution<int>(1, 64)(random);
    size_t next = 0, smallest = sessions, largest = 0;
    for (int i = 1; i <= count; ++i) {
      const SessionRange r = shardRange(sessions, {i, count});
      ASSERT_EQ(r.begin, next) << sessions << " sessions, shard " << i << "/" << count;
      ASSERT_LE(r.begin, r.end);
      smallest = std::min(smallest, r.end - r.begin);
      largest = std::max(largest, r.end - r.begin);
      next = r.end;
    }
    ASSERT_EQ(next, sessions) << count << " shards";
    ASSERT_LE(largest - smallest, 1u) << sessions << " sessions over " << count;
  }
}

TEST(ExportShards, ShardSpecsOutsideOneToNAreRefused) {
  ShardSpec spec;
  std::string error;
  ASSERT_TRUE(parseShardSpec("3/4", &spec, &error)) << error;
  EXPECT_EQ(spec.index, 3);
  EXPECT_EQ(spec.count, 4);
  for (const char* bad : {"0/4", "5/4", "4", "/4", "1/", "-1/4", "1/0", "1/+4", " 1/4", "1/4x",
                          "1/100001", "99999999999999999999/1"}) {
    EXPECT_FALSE(parseShardSpec(bad, &spec, &error)) << bad;
    EXPECT_NE(error.find("--shard: expected I/N"), std::string::npos) << error;
    EXPECT_NE(error.find(bad), std::string::npos) << "the message quotes what was given";
  }
}

TEST(ExportShards, AManifestNamesTheLineOfAMissingJournal) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("cb_manifest_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "P01");
  std::ofstream(dir / "P01" / "session.cbj") << "x";
  std::istringstream good("# the study\n\n  P01/session.cbj  \n");
  const std::vector<std::string> journals = parseExportManifest(good, "m.txt", dir.string());
  ASSERT_EQ(journals.size(), 1u);
  EXPECT_EQ(journals[0], (dir / "P01" / "session.cbj").string());

  std::istringstream missing("P01/session.cbj\n# next\nP02/session.cbj\n");
  try {
    parseExportManifest(missing, "m.txt", dir.string());
    ADD_FAILURE() << "a missing journal was accepted";
  } catch (const StudyInputError& e) {
    EXPECT_NE(std::string(e.what()).find("m.txt:3: journal: '" + (dir / "P02").string()),
              std::string::npos)
        << e.what();
  }
  std::istringstream empty("# nothing\n");
  EXPECT_THROW(parseExportManifest(empty, "m.txt", dir.string()), StudyInputError);
  std::istringstream control("P01/sess\x01ion.cbj\n");
  EXPECT_THROW(parseExportManifest(control, "m.txt", dir.string()), StudyInputError);
  std::filesystem::remove_all(dir);
}

TEST(ExportShards, AShardRecordReadsBackAndATornOneIsRefused) {
  ShardRecord record;
  record.spec = {2, 3};
  record.sessions = {2, 4};
  record.session_ids = {"P03-20261129T070000Z", "P04-20261129T071500Z"};
  record.protocol = "/data/study/thesis_2014.toml";
  record.damaged = {"/data/P04-20261129T071500Z/session.cbj"};
  const std::string text = shardRecordText(record);
  const ShardRecord back = parseShardRecord(text, "shard.txt");
  EXPECT_EQ(back.spec.index, 2);
  EXPECT_EQ(back.spec.count, 3);
  EXPECT_EQ(back.sessions.begin, 2u);
  EXPECT_EQ(back.sessions.end, 4u);
  EXPECT_EQ(back.session_ids, record.session_ids);
  EXPECT_EQ(back.protocol, record.protocol);
  EXPECT_EQ(back.damaged, record.damaged);

  const std::string torn = text.substr(0, text.find("end\n"));
  try {
    parseShardRecord(torn, "shard.txt");
    ADD_FAILURE() << "a record without its end was accepted";
  } catch (const StudyInputError& e) {
    EXPECT_NE(std::string(e.what()).find("end: missing"), std::string::npos) << e.what();
  }
  std::string one_id_short = text;
  one_id_short.erase(one_id_short.find("id P04"), std::string("id P04-20261129T071500Z\n").size());
  EXPECT_THROW(parseShardRecord(one_id_short, "shard.txt"), StudyInputError);
  try {
    parseShardRecord("shard 1/1\nsessions 0 0\ncolour blue\nend\n", "shard.txt");
    ADD_FAILURE() << "an unknown field was accepted";
  } catch (const StudyInputError& e) {
    EXPECT_NE(std::string(e.what()).find("shard.txt:3: 'colour'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace cb
