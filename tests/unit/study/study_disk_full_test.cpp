// The real study runner on a disk that fills up mid-session and frees again: a short session
// (tests/support/short_study.h, `study run --backend replay`) writes its folder onto a 16 MiB
// tmpfs; as the first task begins, the test fills the tmpfs (every write then fails with
// ENOSPC, a real I/O error, not a simulated one) and frees it 5 s later, while the participant
// paints: the first task (3.6 s) ends and its files fail while the disk is full. The runner must
// say so (its problems and the operator's banner), record the outage in session.json, and lose
// nothing: the journal is whole (no gap), holds every pen sample the participant gave and both
// strokes, replays to the volume the runner ended with, and the session completes with its
// answers; the first task's own files (.vdb, .cbvol), kept in memory, are written once space
// returns (journalled `study.files-written`), and replaying the journal gives each task's saved
// .cbvol checksum.
//
// Mounting needs CAP_SYS_ADMIN (root, as in CI's container); without it the test is skipped
// and says so.
#include <gtest/gtest.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <fcntl.h>
#include <sys/mount.h>
#include <unistd.h>

#include "app/study/protocol.h"
#include "drivers/core/journal.h"
#include "tests/support/command_run.h"
#include "tests/support/file_text.h"
#include "tests/support/short_study.h"

namespace cb {
namespace {

namespace fs = std::filesystem;

using cb::test::readText;

size_t countRecords(const JournalReadResult& journal, JournalRecordType type) {
  size_t n = 0;
  for (const JournalRecord& r : journal.records) n += r.type == type;
  return n;
}

// Writes `path` until the file system refuses (ENOSPC); the bytes written.
size_t fillDisk(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  EXPECT_GE(fd, 0) << std::strerror(errno);
  const std::string block(64 * 1024, 'f');
  size_t written = 0;
  for (;;) {
    const ssize_t n = ::write(fd, block.data(), block.size());
    if (n <= 0) {
      EXPECT_EQ(errno, ENOSPC) << std::strerror(errno);
      break;
    }
    written += size_t(n);
  }
  ::close(fd);
  return written;
}

// Runs the short study into `dir`/data (a 16 MiB tmpfs) and fills the disk as the first task
// begins, for 5 s; `run`: what the runner said; `journal_path`: its session's journal.
void runWithTheDiskFullInTheFirstTask(const std::string& dir, const std::string& protocol_path,
                                      const std::string& pen, test::CommandRun* run,
                                      std::string* journal_path) {
  std::thread runner([&] {
    *run =
        test::runCommand(std::string(CB_CLOUDBRUSH_BIN) + " study run " + protocol_path +
                         " --display surfaceless --size " + std::to_string(test::kShortStudyWidth) +
                         "x" + std::to_string(test::kShortStudyHeight) +
                         " --grid 32 --participant 1 --backend replay --journal " + pen +
                         " --end-seconds 0.3 --seconds 90 --data-dir " + dir + "/data");
  });
  // As the first task begins (its marker reached the journal), the disk fills.
  bool in_task = false;
  for (int i = 0; i < 600 && !in_task; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    for (const auto& e : fs::directory_iterator(dir + "/data"))
      if (e.is_directory()) *journal_path = e.path().string() + "/session.cbj";
    in_task = !journal_path->empty() &&
              readText(*journal_path).find("study.stage-begin stage=task") != std::string::npos;
  }
  const std::string filler = dir + "/data/filler";
  size_t filled = 0;
  if (in_task) {
    filled = fillDisk(filler);
    // The first task's stroke and its end (3.6 s after it began) fall in here; the second task
    // ends about 7.2 s after the first began, with room again.
    std::this_thread::sleep_for(std::chrono::seconds(5));
    fs::remove(filler);
  }
  runner.join();
  ASSERT_TRUE(in_task) << "the first task never began\n" << run->out;
  EXPECT_GT(filled, 0u);
}

// Said: a problem (exit status 1) naming the full disk, and that writing came back.
void checkSaid(const test::CommandRun& run, const std::string& folder) {
  EXPECT_EQ(run.status, 1) << run.out;
  // (the first write to fail is the journal's or session.json's, whichever came first)
  EXPECT_NE(run.out.find("problem: storage: "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("No space left on device"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("storage: writing again; nothing was lost"), std::string::npos) << run.out;
  const std::string json = readText(folder + "/session.json");
  EXPECT_NE(json.find("\"status\": \"completed\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"storage\": {\"status\": \"recovered\", \"outages\": [{\"error\": "),
            std::string::npos)
      << json;
  EXPECT_NE(json.find("No space left on device"), std::string::npos) << json;
  EXPECT_EQ(json.find("\"recovered_utc\": null"), std::string::npos) << json;
}

// Kept: the journal is whole and holds everything the participant did; it replays (`replay`) to
// the volume the runner ended with.
void checkKept(const JournalReadResult& journal, const std::string& journal_path,
               const std::string& pen, const std::string& folder, const test::CommandRun& run,
               test::CommandRun* replay) {
  EXPECT_EQ(journal.error, "");
  EXPECT_TRUE(journal.gaps.empty());
  const JournalReadResult input = readJournal(pen);
  EXPECT_EQ(countRecords(journal, JournalRecordType::kPenSample),
            countRecords(input, JournalRecordType::kPenSample))
      << "every pen sample is in the journal";
  EXPECT_EQ(countRecords(journal, JournalRecordType::kStrokeMapped), 2u);
  const std::string text = readText(journal_path);
  EXPECT_NE(text.find("study.end completed"), std::string::npos);
  EXPECT_NE(readText(folder + "/questionnaire.csv").find("C01,4,2,5"), std::string::npos);
  // The journal replays to the volume the runner ended with.
  const size_t at = run.out.find("volume checksum ");
  ASSERT_NE(at, std::string::npos) << run.out;
  const std::string checksum = run.out.substr(at + 16, 16);
  *replay = test::runCommand(std::string(CB_CLOUDBRUSH_BIN) + " replay " + journal_path);
  EXPECT_NE(replay->out.find(checksum), std::string::npos) << checksum << "\n" << replay->out;
}

// The first task's files could not be written at its end: listed as pending, then written
// when space returned; every task's .cbvol is the journal's volume at that task's end.
void checkPendingThenWritten(const JournalReadResult& journal, const std::string& folder,
                             const test::CommandRun& replay) {
  size_t saved_first = std::string::npos, written_first = std::string::npos;
  for (size_t i = 0; i < journal.records.size(); ++i) {
    const JournalRecord& r = journal.records[i];
    if (r.type != JournalRecordType::kMarker) continue;
    const std::string marker(r.text());
    if (marker.rfind("study.saved stage=task task=first", 0) == 0) {
      saved_first = i;
      const size_t pending = marker.find(" pending=");
      EXPECT_NE(pending, std::string::npos) << marker;
      if (pending != std::string::npos) {
        EXPECT_NE(marker.find("tasks/first.cbvol", pending), std::string::npos) << marker;
      }
    }
    if (marker.rfind("study.files-written ", 0) == 0 &&
        marker.find("tasks/first.cbvol") != std::string::npos)
      written_first = i;
  }
  ASSERT_NE(saved_first, std::string::npos) << "no study.saved for the first task";
  ASSERT_NE(written_first, std::string::npos) << "the first task's files were never written";
  EXPECT_GT(written_first, saved_first);
  for (const char* task : {"first", "second"}) {
    EXPECT_TRUE(fs::exists(folder + "/tasks/" + task + ".cbvol")) << task;
    EXPECT_TRUE(fs::exists(folder + "/tasks/" + task + ".vdb")) << task;
    EXPECT_NE(replay.out.find(std::string("task ") + task + ": volume checksum "),
              std::string::npos)
        << replay.out;
  }
  EXPECT_EQ(replay.out.find("DIFFERENT"), std::string::npos) << replay.out;
  EXPECT_EQ(replay.out.find("no " + folder), std::string::npos) << replay.out;
  EXPECT_EQ(replay.status, 0) << replay.out;
  for (const auto& e : fs::recursive_directory_iterator(folder))
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos)
        << "a temporary file: " << e.path();
}

TEST(StudyDiskFull, TheRunnerSaysSoKeepsEverythingAndCarriesOnWhenSpaceReturns) {
  const std::string dir =
      (fs::temp_directory_path() / ("cb_disk_full_" + std::to_string(::getpid()))).string();
  fs::remove_all(dir);
  fs::create_directories(dir + "/data");
  if (::mount("tmpfs", (dir + "/data").c_str(), "tmpfs", 0, "size=16m") != 0) {
    const std::string why = std::strerror(errno);
    fs::remove_all(dir);
    GTEST_SKIP() << "cannot mount a tmpfs here (" << why << ")";
  }
  fs::copy(std::string(CB_SOURCE_DIR) + "/config/study/images", dir + "/images");
  const std::string protocol_path = dir + "/short.toml";
  std::ofstream(protocol_path) << test::kShortStudyProtocol;
  const StudyProtocol protocol = loadStudyProtocol(protocol_path);
  const std::string pen = dir + "/pen.cbj";
  ASSERT_NO_FATAL_FAILURE(test::recordShortStudyPen(protocol, pen));

  test::CommandRun run;
  std::string journal_path;
  ASSERT_NO_FATAL_FAILURE(
      runWithTheDiskFullInTheFirstTask(dir, protocol_path, pen, &run, &journal_path));
  const std::string folder = fs::path(journal_path).parent_path().string();
  ASSERT_NO_FATAL_FAILURE(checkSaid(run, folder));
  const JournalReadResult journal = readJournal(journal_path);
  test::CommandRun replay;
  ASSERT_NO_FATAL_FAILURE(checkKept(journal, journal_path, pen, folder, run, &replay));
  ASSERT_NO_FATAL_FAILURE(checkPendingThenWritten(journal, folder, replay));

  ::umount((dir + "/data").c_str());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace cb
