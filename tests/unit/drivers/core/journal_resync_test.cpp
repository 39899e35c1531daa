// A bad byte in the middle of a journal costs only the records it touches: reading
// resynchronises on the next whole record, in both file versions, and says what it skipped.
// Resuming keeps every byte: damage in the middle stays (readers skip it), a damaged tail is
// moved to a file next to the journal before it is cut.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>

#include <gtest/gtest.h>

#include "drivers/core/journal.h"
#include "drivers/core/journal_framing.h"

namespace cb {
namespace {

std::vector<uint8_t> fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

void writeBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// A real painting session recorded by an earlier version (file version 1, spec 1.1).
const std::string kFixture =
    std::string(CB_SOURCE_DIR) + "/tests/fixtures/journals/morph_spec_1_1.cbj";

// The same records framed in `version`, with each record's [begin, end) offsets.
std::vector<uint8_t> frame(uint32_t version, const std::vector<JournalRecord>& records,
                           std::vector<std::pair<size_t, size_t>>* spans) {
  std::vector<uint8_t> bytes = journalFileHeader(version);
  for (const JournalRecord& r : records) {
    const size_t begin = bytes.size();
    appendJournalRecord(version, uint32_t(r.type), r.t_ns, r.payload.data(), r.payload.size(),
                        &bytes);
    spans->push_back({begin, bytes.size()});
  }
  return bytes;
}

uint32_t seedFromEnv() {
  const char* env = std::getenv("CB_TEST_SEED");
  const uint32_t seed = env ? uint32_t(std::strtoul(env, nullptr, 10)) : 20261129u;
  std::printf("journal resync: seed %u (set CB_TEST_SEED to repeat another)\n", seed);
  return seed;
}

// Flips bytes in three places in the middle of the session; every record that holds no
// flipped byte must come back, in order, and each damaged stretch is reported where it is.
void checkEveryUntouchedRecordIsRecovered(uint32_t version) {
  const JournalReadResult clean = readJournal(kFixture);
  ASSERT_TRUE(clean.error.empty()) << clean.error;
  ASSERT_GT(clean.records.size(), 300u);
  std::vector<std::pair<size_t, size_t>> spans;
  std::vector<uint8_t> bytes = frame(version, clean.records, &spans);
  std::mt19937 rng(seedFromEnv() + version);
  std::vector<bool> hit(spans.size(), false);
  for (int k = 1; k <= 3; ++k) {  // in the second, third and fourth fifth of the file
    const size_t record = spans.size() * size_t(k + 1) / 5 + rng() % 20;
    const size_t at = spans[record].first + rng() % (spans[record].second - spans[record].first);
    bytes[at] ^= uint8_t(1 + rng() % 255);
    hit[record] = true;
  }
  const JournalReadResult damaged = parseJournal(bytes.data(), bytes.size(), "flipped.cbj");
  std::vector<const JournalRecord*> expected;
  for (size_t i = 0; i < spans.size(); ++i)
    if (!hit[i]) expected.push_back(&clean.records[i]);
  ASSERT_EQ(damaged.records.size(), expected.size()) << damaged.error;
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(damaged.records[i].type, expected[i]->type) << "record " << i;
    EXPECT_EQ(damaged.records[i].t_ns, expected[i]->t_ns) << "record " << i;
    EXPECT_EQ(damaged.records[i].payload, expected[i]->payload) << "record " << i;
  }
  // Each gap is exactly one damaged record: its offset and its length.
  std::vector<JournalGap> want;
  for (size_t i = 0; i < spans.size(); ++i)
    if (hit[i]) want.push_back({spans[i].first, spans[i].second - spans[i].first, ""});
  ASSERT_EQ(damaged.gaps.size(), want.size()) << damaged.error;
  for (size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(damaged.gaps[i].offset, want[i].offset);
    EXPECT_EQ(damaged.gaps[i].bytes, want[i].bytes);
  }
  EXPECT_NE(damaged.error.find("flipped.cbj: byte " + std::to_string(want[0].offset)),
            std::string::npos)
      << damaged.error;
  EXPECT_NE(damaged.error.find("in 3 stretches"), std::string::npos) << damaged.error;
  EXPECT_EQ(damaged.intact_bytes, bytes.size());
}

TEST(JournalResync, EveryUntouchedRecordOfARealSessionIsRecoveredInVersion2) {
  checkEveryUntouchedRecordIsRecovered(2);
}

TEST(JournalResync, OldVersion1JournalsResynchroniseToo) {
  checkEveryUntouchedRecordIsRecovered(1);
}

// A damaged length field points past the end: the reader must not trust it.
TEST(JournalResync, ACorruptLengthDoesNotSwallowTheRecordsAfterIt) {
  JournalReadResult clean = readJournal(kFixture);
  std::vector<std::pair<size_t, size_t>> spans;
  std::vector<uint8_t> bytes = frame(2, clean.records, &spans);
  const size_t victim = spans.size() / 2;
  bytes[spans[victim].first + 4 + 4 + 2] = 0x7f;  // the length's third byte: ~8 MB
  const JournalReadResult r = parseJournal(bytes.data(), bytes.size(), "len.cbj");
  EXPECT_EQ(r.records.size(), clean.records.size() - 1);
  ASSERT_EQ(r.gaps.size(), 1u);
  EXPECT_EQ(r.gaps[0].offset, spans[victim].first);
  EXPECT_EQ(r.gaps[0].bytes, spans[victim].second - spans[victim].first);
}

TEST(JournalResync, ResumeKeepsMiddleDamageAndMovesATornTailAsideByteForByte) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "cb_journal_resume_flip.cbj").string();
  const JournalReadResult clean = readJournal(kFixture);
  std::vector<std::pair<size_t, size_t>> spans;
  std::vector<uint8_t> bytes = frame(2, clean.records, &spans);
  const size_t middle = spans.size() / 2;
  bytes[spans[middle].first + 22] ^= 0x40;
  const size_t last = spans.size() - 1;
  bytes.resize(spans[last].first + 9);  // a torn last record
  writeBytes(path, bytes);
  const std::string aside = path + ".damaged-at-" + std::to_string(spans[last].first);
  std::filesystem::remove(aside);
  std::string warning;
  {
    JournalWriter w;
    ASSERT_TRUE(w.openForAppend(path, &warning)) << w.error();
    ASSERT_TRUE(w.append(JournalRecordType::kMarker, 42, "after the resume"));
  }
  EXPECT_NE(warning.find("moved to " + aside), std::string::npos) << warning;
  EXPECT_NE(warning.find("byte " + std::to_string(spans[middle].first)), std::string::npos)
      << warning;
  // The tail's 9 bytes are in the file beside it; the journal's bytes up to the tail are as
  // they were, the flipped record included.
  EXPECT_EQ(fileBytes(aside),
            std::vector<uint8_t>(bytes.begin() + long(spans[last].first), bytes.end()));
  const std::vector<uint8_t> after = fileBytes(path);
  ASSERT_GT(after.size(), spans[last].first);
  EXPECT_TRUE(std::equal(bytes.begin(), bytes.begin() + long(spans[last].first), after.begin()));
  const JournalReadResult resumed = readJournal(path);
  ASSERT_EQ(resumed.records.size(), clean.records.size() - 2 + 1) << resumed.error;
  EXPECT_EQ(resumed.records.back().text(), "after the resume");
  EXPECT_EQ(resumed.gaps.size(), 1u);
  std::filesystem::remove(path);
  std::filesystem::remove(aside);
}

}  // namespace
}  // namespace cb
