#include "drivers/core/journal.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

namespace cb {
namespace {

PenSample sampleAt(int i) {
  PenSample s;
  s.t_ns = 1000000LL * i;
  s.x_raw = 100 + i, s.y_raw = 200 - i;
  s.x_mm = 0.5 * i, s.y_mm = 1.25 * i;
  s.pressure_raw = 40 * i, s.pressure = 0.01f * i;
  s.tilt_x_raw = -i, s.tilt_y_raw = i, s.tilt_x_deg = -1.5f * i, s.tilt_y_deg = 0.75f * i;
  s.distance_raw = 3, s.distance = 0.1f;
  s.buttons = i % 2 ? uint32_t(kPenTip) : 0u;
  s.tool = PenTool::kPen, s.tool_id = 0x802, s.tool_serial = 0xABCDEF01ULL;
  s.in_proximity = true;
  return s;
}

std::string tempPath(const char* name) {
  return (std::filesystem::temp_directory_path() / name).string();
}

TEST(Journal, PenSampleRoundTripsExactly) {
  PenSample s = sampleAt(7);
  auto d = decodePenSample(encodePenSample(s));
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(encodePenSample(*d), encodePenSample(s));
  EXPECT_EQ(d->x_mm, s.x_mm);
  EXPECT_EQ(d->tool_serial, s.tool_serial);
  EXPECT_EQ(d->tool, PenTool::kPen);
}

TEST(Journal, WrongSizedPayloadIsRejected) {
  auto p = encodePenSample(sampleAt(1));
  p.pop_back();
  EXPECT_FALSE(decodePenSample(p).has_value());
}

TEST(Journal, FileRoundTripKeepsOrderAndTypes) {
  std::string path = tempPath("cb_journal_roundtrip.cbj");
  {
    JournalWriter w;
    ASSERT_TRUE(w.open(path)) << w.error();
    ASSERT_TRUE(w.append(JournalRecordType::kCalibration, 5, "pressure_curve = [0, 0, 100, 100]"));
    for (int i = 0; i < 50; ++i) ASSERT_TRUE(w.appendPenSample(sampleAt(i)));
    ASSERT_TRUE(w.append(JournalRecordType::kMode, 99, "erase"));
  }
  JournalReadResult r = readJournal(path);
  EXPECT_TRUE(r.error.empty()) << r.error;
  ASSERT_EQ(r.records.size(), 52u);
  EXPECT_EQ(r.records[0].type, JournalRecordType::kCalibration);
  EXPECT_EQ(r.records[0].text(), "pressure_curve = [0, 0, 100, 100]");
  for (int i = 0; i < 50; ++i) {
    auto s = decodePenSample(r.records[1 + i].payload);
    ASSERT_TRUE(s.has_value());
    EXPECT_EQ(s->x_raw, 100 + i);
  }
  EXPECT_EQ(r.records[51].text(), "erase");
  std::filesystem::remove(path);
}

TEST(Journal, TruncatedTailKeepsEarlierRecordsAndNamesOffset) {
  std::string path = tempPath("cb_journal_trunc.cbj");
  {
    JournalWriter w;
    ASSERT_TRUE(w.open(path));
    for (int i = 0; i < 10; ++i) ASSERT_TRUE(w.appendPenSample(sampleAt(i)));
  }
  auto size = std::filesystem::file_size(path);
  std::filesystem::resize_file(path, size - 7);
  JournalReadResult r = readJournal(path);
  EXPECT_EQ(r.records.size(), 9u);
  EXPECT_NE(r.error.find(path), std::string::npos);
  EXPECT_NE(r.error.find("truncated"), std::string::npos);
  EXPECT_NE(r.error.find("byte "), std::string::npos);
  std::filesystem::remove(path);
}

TEST(Journal, CorruptByteIsCaughtByChecksum) {
  JournalWriter w;
  std::string path = tempPath("cb_journal_crc.cbj");
  ASSERT_TRUE(w.open(path));
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(w.appendPenSample(sampleAt(i)));
  w.close();
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(16 + 20 + 4);  // inside the first record's payload (after marker and head)
  f.put('\x7f');
  f.close();
  JournalReadResult r = readJournal(path);
  // Only the damaged record is lost: reading resynchronises on the next one.
  EXPECT_EQ(r.records.size(), 2u);
  EXPECT_NE(r.error.find("checksum"), std::string::npos);
  ASSERT_EQ(r.gaps.size(), 1u);
  EXPECT_EQ(r.gaps[0].offset, 16u);
  EXPECT_EQ(r.gaps[0].bytes, 4u + 16 + 82 + 4);
  std::filesystem::remove(path);
}

TEST(Journal, RejectsForeignFilesAndNewerVersions) {
  const uint8_t junk[] = "this is not a journal at all";
  EXPECT_NE(parseJournal(junk, sizeof junk).error.find("bad magic"), std::string::npos);
  uint8_t header[16] = {'C', 'B', 'J', 'O', 'U', 'R', 'N', 'L', 99, 0, 0, 0, 0, 0, 0, 0};
  EXPECT_NE(parseJournal(header, sizeof header).error.find("version 99"), std::string::npos);
}

TEST(Journal, UnknownRecordTypesAreSkippedNotFatal) {
  std::string path = tempPath("cb_journal_unknown.cbj");
  {
    JournalWriter w;
    ASSERT_TRUE(w.open(path));
    ASSERT_TRUE(w.append(JournalRecordType(1000), 1, "from the future"));
    ASSERT_TRUE(w.appendPenSample(sampleAt(1)));
  }
  JournalReadResult r = readJournal(path);
  EXPECT_TRUE(r.error.empty());
  EXPECT_EQ(r.skipped_unknown, 1u);
  EXPECT_EQ(r.records.size(), 1u);
  std::filesystem::remove(path);
}

int64_t steadyNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// Records older than a second reach the disk at the next timer tick or append; newer
// ones wait for the stroke end (sync) or the second to pass.
TEST(Journal, SyncIfDueSyncsOnlyRecordsOlderThanTheInterval) {
  const std::string path = tempPath("cb_journal_sync.cbj");
  JournalWriter w;
  ASSERT_TRUE(w.open(path));
  const uint64_t after_open = w.syncCount();
  EXPECT_FALSE(w.hasUnsyncedRecords());
  const int64_t before = steadyNs();
  ASSERT_TRUE(w.appendPenSample(sampleAt(1)));
  EXPECT_TRUE(w.hasUnsyncedRecords());
  EXPECT_TRUE(w.syncIfDue(before + 500'000'000));  // half a second: not yet
  EXPECT_EQ(w.syncCount(), after_open);
  EXPECT_TRUE(w.hasUnsyncedRecords());
  EXPECT_TRUE(w.syncIfDue(steadyNs() + JournalWriter::kJournalSyncIntervalNs));
  EXPECT_EQ(w.syncCount(), after_open + 1);
  EXPECT_FALSE(w.hasUnsyncedRecords());
  EXPECT_TRUE(w.syncIfDue(steadyNs() + 10 * JournalWriter::kJournalSyncIntervalNs));
  EXPECT_EQ(w.syncCount(), after_open + 1) << "nothing new to sync";
  ASSERT_TRUE(w.sync());
  EXPECT_EQ(w.syncCount(), after_open + 2);
  w.close();
  std::filesystem::remove(path);
}

// A crash mid-record leaves a torn tail: reading keeps every whole record and says where it
// broke; re-opening for append moves the tail to a file beside it and the next records follow
// the last whole one.
TEST(Journal, OpenForAppendMovesATornTailAsideAndCarriesOn) {
  const std::string path = tempPath("cb_journal_append.cbj");
  {
    JournalWriter w;
    ASSERT_TRUE(w.open(path));
    for (int i = 0; i < 5; ++i) ASSERT_TRUE(w.appendPenSample(sampleAt(i)));
  }
  const auto whole = std::filesystem::file_size(path);
  std::filesystem::resize_file(path, whole - 30);  // inside the fifth record
  const JournalReadResult torn = readJournal(path);
  EXPECT_EQ(torn.records.size(), 4u);
  EXPECT_NE(torn.error.find("byte "), std::string::npos) << torn.error;
  EXPECT_EQ(torn.intact_bytes, whole - (4 + 16 + 82 + 4));
  const std::string aside = path + ".damaged-at-" + std::to_string(torn.intact_bytes);
  {
    JournalWriter w;
    std::string warning;
    ASSERT_TRUE(w.openForAppend(path, &warning)) << w.error();
    EXPECT_NE(warning.find("last 76 bytes"), std::string::npos) << warning;
    EXPECT_NE(warning.find("moved to " + aside), std::string::npos) << warning;
    EXPECT_EQ(std::filesystem::file_size(aside), 76u);
    for (int i = 10; i < 13; ++i) ASSERT_TRUE(w.appendPenSample(sampleAt(i)));
  }
  const JournalReadResult resumed = readJournal(path);
  EXPECT_TRUE(resumed.error.empty()) << resumed.error;
  ASSERT_EQ(resumed.records.size(), 7u);
  EXPECT_EQ(decodePenSample(resumed.records[3].payload)->x_raw, 103);
  EXPECT_EQ(decodePenSample(resumed.records[4].payload)->x_raw, 110);
  EXPECT_EQ(resumed.intact_bytes, std::filesystem::file_size(path));
  {
    // A whole journal re-opens without a warning; a foreign file is refused and left alone.
    JournalWriter w;
    std::string warning = "x";
    ASSERT_TRUE(w.openForAppend(path, &warning)) << w.error();
    EXPECT_TRUE(warning.empty()) << warning;
  }
  const std::string foreign = tempPath("cb_journal_foreign.txt");
  std::ofstream(foreign) << "a shopping list, not a journal";
  JournalWriter w;
  std::string warning;
  EXPECT_FALSE(w.openForAppend(foreign, &warning));
  EXPECT_NE(w.error().find("bad magic"), std::string::npos) << w.error();
  EXPECT_EQ(std::filesystem::file_size(foreign), 30u);
  std::filesystem::remove(foreign);
  std::filesystem::remove(aside);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace cb
