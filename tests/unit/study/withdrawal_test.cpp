// Withdrawal on a made-up study data tree: everything of one participant goes, nobody else's.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "app/study/participant_withdrawal.h"

namespace cb {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

class Withdrawal : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::path(::testing::TempDir()) /
            ("withdrawal-" +
             std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(root_);
    data_ = root_ / "data";
    write(data_ / "sessions/P03_2026-11-02/session.cbj", "journal P03");
    write(data_ / "sessions/P03_2026-11-02/volumes/cloud1.vdb", "vdb");
    write(data_ / "sessions/P30_2026-11-03/session.cbj", "journal P30");
    write(data_ / "sessions/P3/session.cbj", "journal P3");
    write(data_ / "sessions/P04_2026-11-04/session.cbj", "journal P04");
    write(data_ / "exports/P03.inkml", "<ink/>");
    write(data_ / "questionnaire.csv",
          "participant,age,Q1,Q2\nP01,30,4,5\nP03,25,\"3\",NA\nP30,41,2,2\nP04,22,5,5\n");
    write(data_ / "exports/strokes.csv",
          "session,stroke,start_s\nP03_2026-11-02,1,0.5\nP30_2026-11-03,1,0.2\n"
          "P03_2026-11-02,2,1.5\n");
    write(data_ / "notes.txt", "P30 was late; P04 fine\n");
    write(root_ / "keys/key.csv", "participant,name,contact\nP03,Ann,a@x\nP04,Bo,b@x\n");
  }
  fs::path root_, data_;
};

TEST_F(Withdrawal, RemovesOneParticipantsFoldersRowsAndKeyEntryOnly) {
  const WithdrawalResult result =
      withdrawParticipant(data_, "P03", root_ / "keys/key.csv", /*dry_run=*/false);
  EXPECT_EQ(result.removed_paths.size(), 2u);
  EXPECT_FALSE(fs::exists(data_ / "sessions/P03_2026-11-02"));
  EXPECT_FALSE(fs::exists(data_ / "exports/P03.inkml"));
  EXPECT_TRUE(fs::exists(data_ / "sessions/P30_2026-11-03/session.cbj"));
  EXPECT_TRUE(fs::exists(data_ / "sessions/P3/session.cbj"));
  EXPECT_TRUE(fs::exists(data_ / "sessions/P04_2026-11-04/session.cbj"));
  EXPECT_EQ(read(data_ / "questionnaire.csv"),
            "participant,age,Q1,Q2\nP01,30,4,5\nP30,41,2,2\nP04,22,5,5\n");
  EXPECT_EQ(read(data_ / "exports/strokes.csv"), "session,stroke,start_s\nP30_2026-11-03,1,0.2\n");
  EXPECT_EQ(read(root_ / "keys/key.csv"), "participant,name,contact\nP04,Bo,b@x\n");
  ASSERT_EQ(result.removed_rows.size(), 3u);
  int rows = 0;
  for (const CsvRowRemoval& removal : result.removed_rows) rows += removal.rows;
  EXPECT_EQ(rows, 4);
  EXPECT_TRUE(result.still_mentioning.empty());
}

TEST_F(Withdrawal, DryRunChangesNothingAndLeftoversAreListed) {
  const std::string before = read(data_ / "questionnaire.csv");
  const WithdrawalResult dry = withdrawParticipant(data_, "P30", {}, /*dry_run=*/true);
  EXPECT_EQ(dry.removed_paths.size(), 1u);
  EXPECT_EQ(read(data_ / "questionnaire.csv"), before);
  EXPECT_TRUE(fs::exists(data_ / "sessions/P30_2026-11-03"));
  const WithdrawalResult done = withdrawParticipant(data_, "P30", {}, /*dry_run=*/false);
  ASSERT_EQ(done.still_mentioning.size(), 1u);  // notes.txt is free text: listed, not edited
  EXPECT_EQ(done.still_mentioning[0].filename(), "notes.txt");
  EXPECT_EQ(read(data_ / "notes.txt"), "P30 was late; P04 fine\n");
}

TEST_F(Withdrawal, RefusesIdsThatMatchNothingOrAreNotIds) {
  EXPECT_THROW(withdrawParticipant(data_, "P99", {}, false), WithdrawalError);
  EXPECT_THROW(withdrawParticipant(data_, "../keys", {}, false), WithdrawalError);
  EXPECT_THROW(withdrawParticipant(data_, "", {}, false), WithdrawalError);
  EXPECT_THROW(withdrawParticipant(data_ / "missing", "P03", {}, false), WithdrawalError);
  EXPECT_TRUE(fs::exists(data_ / "sessions/P03_2026-11-02"));
}

TEST_F(Withdrawal, AnUnsplittableCsvStopsEverythingBeforeDeleting) {
  write(data_ / "broken.csv", "participant,Q1\nP03,\"unclosed\n");
  try {
    withdrawParticipant(data_, "P03", {}, false);
    FAIL() << "accepted";
  } catch (const WithdrawalError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.csv:2: unclosed quote"), std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(fs::exists(data_ / "sessions/P03_2026-11-02/session.cbj"));
  EXPECT_NE(read(data_ / "questionnaire.csv").find("P03"), std::string::npos);
}

}  // namespace
}  // namespace cb
