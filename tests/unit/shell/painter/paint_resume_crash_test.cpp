// Crash test ("Evidence"): a recorded session is replayed into the real painter
// (`cloudbrush paint --display surfaceless --backend replay --resume FILE`), which is killed
// with SIGKILL at 20 random points and restarted on the same file each time. Every restart
// resumes the session; no completed stroke is ever lost; and the final volume equals the one an
// uninterrupted run paints, and `cloudbrush replay` of the resumed journal reproduces it. The
// seed is printed (CB_TEST_SEED=N repeats a run).
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "app/session/paint_session.h"
#include "app/session/synthetic_session.h"

#include "tests/support/command_run.h"
#include "tests/support/reference_journal.h"
#include "tests/support/test_seed.h"
#include "tests/support/file_text.h"

namespace cb {
namespace {

constexpr int kW = 320, kH = 180;

std::string capture(const std::string& text, const std::string& pattern) {
  std::smatch match;
  return std::regex_search(text, match, std::regex(pattern)) ? match[1].str() : std::string();
}

// Strokes completed in a journal: tip-down runs of pen samples that ended with the tip up.
int completedStrokes(const std::string& path) {
  const JournalReadResult journal = readJournal(path);
  int strokes = 0;
  bool down = false;
  for (const JournalRecord& r : journal.records) {
    if (r.type != JournalRecordType::kPenSample) continue;
    const bool tip = (decodePenSample(r.payload)->buttons & kPenTip) != 0;
    if (down && !tip) ++strokes;
    down = tip;
  }
  return strokes;
}

std::string paintCommand(const std::string& pen, const std::string& session) {
  return std::string(CB_CLOUDBRUSH_BIN) + " paint --display surfaceless --size " +
         std::to_string(kW) + "x" + std::to_string(kH) +
         " --grid 64 --orbit 0 --backend replay --journal " + pen + " --resume " + session;
}

// Starts the painter with its output in `log`; returns its pid.
pid_t spawn(const std::string& command, const std::string& log) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const std::string line = "exec " + command + " > '" + log + "' 2>&1";
    ::execl("/bin/sh", "sh", "-c", line.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return pid;
}

// Whether the child has exited, without reaping it (its status is read after the kill).
bool exited(pid_t pid) {
  siginfo_t info{};
  return ::waitid(P_PID, id_t(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid;
}

using cb::test::readText;

TEST(PaintResumeCrash, KilledTwentyTimesTheSessionResumesAndEndsWithTheSameVolume) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("cb_paint_crash_" + std::to_string(::getpid())))
          .string();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string pen = dir + "/pen.cbj";
  std::string error;
  // The pen's input: the reference strokes three times over, 0.3 s apart (about 11 s of pen).
  ASSERT_TRUE(test::recordReferenceJournal(pen, kW, kH, 3, &error)) << error;
  const int source_strokes = completedStrokes(pen);
  ASSERT_EQ(source_strokes, 6);

  // Uninterrupted.
  const test::CommandRun whole = test::runCommand(paintCommand(pen, dir + "/whole.cbj"));
  ASSERT_EQ(whole.status, 0) << whole.out;
  const std::string expected = capture(whole.out, "volume checksum ([0-9a-f]{16})");
  ASSERT_FALSE(expected.empty()) << whole.out;
  EXPECT_EQ(completedStrokes(dir + "/whole.cbj"), source_strokes);

  const unsigned seed = cb::test::testSeed("paint crash test");
  std::mt19937 random(seed);
  // One kill in five lands during startup (display, renderer, replay of the journal so far);
  // the others once the pen plays into the painter (it printed "pen connected"), 0–1 s into
  // the painting, whatever the machine's speed.
  std::uniform_int_distribution<int> delay_ms(0, 1000), startup_ms(0, 300), during_startup(0, 4);
  const std::string session = dir + "/session.cbj";
  int kills = 0, resumes = 0, finished_before_kill = 0, strokes_before = 0;
  for (int i = 0; i < 20; ++i) {
    const std::string log = dir + "/run" + std::to_string(i) + ".log";
    const bool in_startup = during_startup(random) == 0;
    const int wait = in_startup ? startup_ms(random) : delay_ms(random);
    const pid_t pid = spawn(paintCommand(pen, session), log);
    ASSERT_GT(pid, 0);
    if (!in_startup)
      for (int t = 0; t < 3000; ++t) {  // at most 30 s
        const std::string so_far = readText(log);
        if (so_far.find("pen connected") != std::string::npos || exited(pid)) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
    std::this_thread::sleep_for(std::chrono::milliseconds(wait));
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    const std::string out = readText(log);
    if (WIFSIGNALED(status))
      ++kills;
    else
      ++finished_before_kill;
    if (out.find("resumed ") != std::string::npos) ++resumes;
    const int strokes = std::filesystem::exists(session) ? completedStrokes(session) : 0;
    std::printf("kill %2d %4d ms after %s: %s, %d strokes in the journal\n", i, wait,
                in_startup ? "start" : "the pen connected",
                WIFSIGNALED(status) ? "killed" : "had finished", strokes);
    EXPECT_GE(strokes, strokes_before) << "a completed stroke was lost at kill " << i << "\n"
                                       << out;
    EXPECT_TRUE(WIFSIGNALED(status) || WEXITSTATUS(status) == 0) << out;
    strokes_before = strokes;
  }
  EXPECT_GE(kills, 10) << "most runs should have been killed, not finished";
  EXPECT_GE(resumes, 5) << "restarts resumed the session";

  const test::CommandRun last = test::runCommand(paintCommand(pen, session));
  ASSERT_EQ(last.status, 0) << last.out;
  EXPECT_NE(last.out.find("resumed "), std::string::npos) << last.out;
  EXPECT_EQ(capture(last.out, "volume checksum ([0-9a-f]{16})"), expected) << last.out;
  EXPECT_EQ(completedStrokes(session), source_strokes);
  const test::CommandRun replay =
      test::runCommand(std::string(CB_CLOUDBRUSH_BIN) + " replay " + session);
  EXPECT_EQ(replay.status, 0) << replay.out;
  EXPECT_EQ(capture(replay.out, "volume checksum: ([0-9a-f]{16})"), expected) << replay.out;
  EXPECT_NE(replay.out.find(" 6 strokes mapped"), std::string::npos) << replay.out;
  std::printf("%d killed, %d had finished, %d resumed; final checksum %s\n", kills,
              finished_before_kill, resumes, expected.c_str());
  if (!HasFailure()) std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cb
