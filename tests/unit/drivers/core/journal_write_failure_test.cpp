// A write that really fails (the file size limit, RLIMIT_FSIZE, makes write() return EFBIG as a
// full disk returns ENOSPC) must not leave a torn record in the journal, and the records that
// could not be written are written, in order, once writing works again.
#include <csignal>
#include <filesystem>

#include <sys/resource.h>

#include <gtest/gtest.h>

#include "drivers/core/journal.h"

namespace cb {
namespace {

class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    std::signal(SIGXFSZ, SIG_IGN);  // write() then fails with EFBIG instead of killing us
    getrlimit(RLIMIT_FSIZE, &saved_);
    rlimit limit = saved_;
    limit.rlim_cur = bytes;
    EXPECT_EQ(setrlimit(RLIMIT_FSIZE, &limit), 0);
  }
  ~FileSizeLimit() { lift(); }
  void lift() { setrlimit(RLIMIT_FSIZE, &saved_); }

 private:
  rlimit saved_{};
};

std::string textOf(int i) {
  return "marker " + std::to_string(i) + std::string(size_t(i % 7) * 5, '.');
}

TEST(JournalWriteFailure, AFullFileSystemLeavesNoTornRecordAndLosesNothingWhenSpaceReturns) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "cb_journal_write_failure.cbj").string();
  JournalWriter w;
  ASSERT_TRUE(w.open(path)) << w.error();
  FileSizeLimit limit(4000);  // the journal reaches it after about 70 records
  int written = 0, failed_at = -1;
  for (int i = 0; i < 120; ++i) {
    const bool ok = w.append(JournalRecordType::kMarker, i, textOf(i));
    if (ok) ++written;
    if (!ok && failed_at < 0) failed_at = i;
  }
  ASSERT_GE(failed_at, 0) << "the limit was never reached";
  EXPECT_TRUE(w.failing());
  EXPECT_NE(w.error().find("write failed"), std::string::npos) << w.error();
  EXPECT_NE(w.error().find("File too large"), std::string::npos) << w.error();
  // While failing, the file ends exactly after its last whole record.
  const JournalReadResult during = readJournal(path);
  EXPECT_TRUE(during.error.empty()) << during.error;
  EXPECT_EQ(during.records.size(), size_t(failed_at));
  EXPECT_EQ(during.intact_bytes, std::filesystem::file_size(path));
  EXPECT_FALSE(w.sync());
  limit.lift();  // space returns
  ASSERT_TRUE(w.append(JournalRecordType::kMarker, 120, textOf(120))) << w.error();
  EXPECT_FALSE(w.failing());
  w.close();
  const JournalReadResult after = readJournal(path);
  EXPECT_TRUE(after.error.empty()) << after.error;
  ASSERT_EQ(after.records.size(), 121u);
  for (int i = 0; i <= 120; ++i) {
    EXPECT_EQ(after.records[size_t(i)].text(), textOf(i));
    EXPECT_EQ(after.records[size_t(i)].t_ns, i);
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace cb
