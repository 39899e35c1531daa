// A runner killed in the middle of a task leaves that task's volume files (`tasks/ID.cbvol`,
// `.vdb`) as of its last stroke: the runner writes them as the task goes (at a stroke's end,
// atomically), not only when the task ends. The real `cloudbrush study run` (surfaceless, the
// short study's recorded pen, tests/support/short_study.h) is killed with SIGKILL as soon as the
// first task's .cbvol appears, before the task ends; then:
// - the runner had not closed the task (no `study.stage-closing` in its log, no `study.saved` in
//   the journal): the file was written as the task went, not at its end;
// - tasks/first.cbvol reads back, holds the stroke (density), and its checksum is the volume a
//   replay of the killed journal gives (`cloudbrush replay`): nothing painted is missing;
// - `study run --resume` finishes the session; the task's file at its end holds the same stroke.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <thread>

#include "app/session/session_replay.h"
#include "app/study/protocol.h"
#include "app/volume/volume_file.h"
#include "drivers/core/journal.h"

#include "tests/support/command_run.h"
#include "tests/support/file_text.h"
#include "tests/support/short_study.h"

namespace cb {
namespace {

namespace fs = std::filesystem;

std::string capture(const std::string& text, const std::string& pattern) {
  std::smatch match;
  return std::regex_search(text, match, std::regex(pattern)) ? match[1].str() : std::string();
}

bool journalSays(const std::string& path, const std::string& prefix) {
  for (const JournalRecord& r : readJournal(path).records)
    if (r.type == JournalRecordType::kMarker && std::string(r.text()).rfind(prefix, 0) == 0)
      return true;
  return false;
}

TEST(StudyTaskSoFar, KilledMidTaskTheTasksVolumeFilesHoldItsStrokes) {
  const std::string dir =
      (fs::temp_directory_path() / ("cb_study_so_far_" + std::to_string(::getpid()))).string();
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy(std::string(CB_SOURCE_DIR) + "/config/study/images", dir + "/images");
  const std::string protocol_path = dir + "/short.toml";
  std::ofstream(protocol_path) << test::kShortStudyProtocol;
  const StudyProtocol protocol = loadStudyProtocol(protocol_path);
  const std::string pen = dir + "/pen.cbj";
  ASSERT_NO_FATAL_FAILURE(test::recordShortStudyPen(protocol, pen));
  const std::string folder = dir + "/data/C01-killed";
  const std::string command = std::string(CB_CLOUDBRUSH_BIN) + " study run " + protocol_path +
                              " --display surfaceless --size " +
                              std::to_string(test::kShortStudyWidth) + "x" +
                              std::to_string(test::kShortStudyHeight) +
                              " --grid 64 --participant 1 --backend replay --journal " + pen +
                              " --end-seconds 0.3 --seconds 90 --resume " + folder;
  const std::string log = dir + "/killed.log";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string line = "exec " + command + " > '" + log + "' 2>&1";
    ::execl("/bin/sh", "sh", "-c", line.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // The first task runs about 3.6 s on the pen's time line, its stroke ending some 2 s before
  // the task does: killed as soon as the file is there (polled every 5 ms, at most 60 s).
  const std::string so_far = folder + "/tasks/first.cbvol";
  bool appeared = false;
  for (int i = 0; i < 12000 && !appeared; ++i) {
    appeared = fs::exists(so_far);
    if (!appeared) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  const std::string out = test::readText(log);
  ASSERT_TRUE(appeared) << "tasks/first.cbvol never appeared while the task ran\n" << out;
  ASSERT_TRUE(WIFSIGNALED(status)) << "the runner had ended before the kill\n" << out;
  const std::string journal = folder + "/session.cbj";
  ASSERT_TRUE(journalSays(journal, "study.stage-begin stage=task task=first")) << out;
  // Mid-task: the runner (which logs each record as it makes it, unbuffered) had not closed
  // the task; the file was not the task's end's.
  ASSERT_EQ(out.find("study.stage-closing stage=task task=first"), std::string::npos)
      << "killed too late: the task had ended (its stroke ends ~2 s before)\n"
      << out;
  ASSERT_FALSE(journalSays(journal, "study.saved stage=task task=first")) << out;

  const Volume so_far_volume = loadVolume(so_far);
  EXPECT_TRUE(so_far_volume.hasDensity()) << "the task's stroke is in the file";
  // A copy of the killed journal, replayed: its volume is the file's.
  fs::copy_file(journal, dir + "/killed.cbj");
  const test::CommandRun replay =
      test::runCommand(std::string(CB_CLOUDBRUSH_BIN) + " replay " + dir + "/killed.cbj");
  ASSERT_EQ(replay.status, 0) << replay.out;
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx",
                static_cast<unsigned long long>(volumeChecksum(so_far_volume)));
  EXPECT_EQ(capture(replay.out, "volume checksum: ([0-9a-f]{16})"), hex)
      << "the file is the volume the journal holds\n"
      << replay.out;

  // Carried on: the session ends and the task is saved at its end, still its one stroke.
  const test::CommandRun resumed = test::runCommand(command);
  ASSERT_EQ(resumed.status, 0) << resumed.out;
  EXPECT_NE(resumed.out.find("stage done"), std::string::npos) << resumed.out;
  EXPECT_TRUE(journalSays(journal, "study.saved stage=task task=first"));
  EXPECT_EQ(volumeChecksum(loadVolume(so_far)), volumeChecksum(so_far_volume));
  EXPECT_TRUE(fs::exists(folder + "/tasks/second.cbvol"));
  if (!HasFailure()) fs::remove_all(dir);
}

}  // namespace
}  // namespace cb
