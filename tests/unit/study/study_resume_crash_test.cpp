// Crash test for study sessions ("Evidence"): a recorded pen session is replayed into
// the real study runner (`cloudbrush study run --display surfaceless --backend replay --resume
// FOLDER`), which is killed with SIGKILL at seeded random points and restarted on the same
// folder each time. Every restart resumes the session (stage, task, answers, clock); no pen
// sample, completed stroke or answer is ever lost or doubled; and at the end the folder holds
// what an uninterrupted run leaves: the same questionnaire answers, the same stage and answer
// records, the same task volumes, and the same final volume (also from `cloudbrush replay` of
// the resumed journal). The seed is printed (CB_TEST_SEED=N repeats a run); CB_CRASH_KILLS sets
// the number of kills (ctest: 5 in CI, 20 in the `slow` variant).
//
// The protocol and the pen are tests/support/short_study.h's: consent, the participant's code,
// an introduction, a one-step tutorial (an empty sky), 1.8 s of free drawing, two tasks of
// 3.6 s (a stroke each), three Likert items, tapped on the runner's own targets.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
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

#include "app/study/protocol.h"
#include "drivers/core/journal.h"

#include "tests/support/command_run.h"
#include "tests/support/file_text.h"
#include "tests/support/short_study.h"
#include "tests/support/test_seed.h"

namespace cb {
namespace {

constexpr int kW = test::kShortStudyWidth, kH = test::kShortStudyHeight;

using cb::test::readText;

std::string capture(const std::string& text, const std::string& pattern) {
  std::smatch match;
  return std::regex_search(text, match, std::regex(pattern)) ? match[1].str() : std::string();
}

struct JournalCounts {
  std::vector<int64_t> sample_times;  // every pen sample, in order
  int strokes = 0;                    // tip-down runs that ended with the tip up
  std::vector<std::string> answers;   // study.answer records
  std::vector<std::string> stages;    // study.stage-begin, study.saved and study.answer records
};

JournalCounts countJournal(const std::string& path) {
  JournalCounts c;
  const JournalReadResult journal = readJournal(path);
  bool down = false;
  for (const JournalRecord& r : journal.records) {
    if (r.type == JournalRecordType::kPenSample) {
      const PenSample s = *decodePenSample(r.payload);
      c.sample_times.push_back(s.t_ns);
      const bool tip = (s.buttons & kPenTip) != 0;
      if (down && !tip) ++c.strokes;
      down = tip;
    } else if (r.type == JournalRecordType::kMarker) {
      const std::string text(r.text());
      if (text.rfind("study.answer ", 0) == 0) c.answers.push_back(text);
      if (text.rfind("study.answer ", 0) == 0 || text.rfind("study.stage-begin ", 0) == 0 ||
          text.rfind("study.saved ", 0) == 0)
        c.stages.push_back(text);
    }
  }
  return c;
}

pid_t spawn(const std::string& command, const std::string& log) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const std::string line = "exec " + command + " > '" + log + "' 2>&1";
    ::execl("/bin/sh", "sh", "-c", line.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return pid;
}

bool exited(pid_t pid) {
  siginfo_t info{};
  return ::waitid(P_PID, id_t(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid;
}

// The crash test's fixture: the protocol and recorded pen in `dir`, and what the uninterrupted
// run (`whole`) left: its final volume's checksum, its journal's counts, its answers.
struct CrashRun {
  std::string dir, protocol_path, pen, whole, expected, answers;
  JournalCounts source, reference_counts;

  // The runner on the recorded pen, resuming (or starting) the session in `folder`.
  std::string command(const std::string& folder) const {
    return std::string(CB_CLOUDBRUSH_BIN) + " study run " + protocol_path +
           " --display surfaceless --size " + std::to_string(kW) + "x" + std::to_string(kH) +
           " --grid 64 --participant 1 --backend replay --journal " + pen +
           " --end-seconds 0.3 --seconds 90 --resume " + folder;
  }
};

// Records the pen and runs the session uninterrupted; a penless resume of it keeps its pen.
void runUninterrupted(CrashRun* c) {
  const std::string& dir = c->dir;
  std::filesystem::create_directories(dir);
  std::filesystem::copy(std::string(CB_SOURCE_DIR) + "/config/study/images", dir + "/images");
  c->protocol_path = dir + "/crash.toml";
  const std::string& protocol_path = c->protocol_path;
  std::ofstream(protocol_path) << test::kShortStudyProtocol;
  const StudyProtocol protocol = loadStudyProtocol(protocol_path);
  c->pen = dir + "/pen.cbj";
  const std::string& pen = c->pen;
  ASSERT_NO_FATAL_FAILURE(test::recordShortStudyPen(protocol, pen));
  c->source = countJournal(pen);
  ASSERT_EQ(c->source.strokes, 6 + 2) << "six taps and two strokes";

  // Uninterrupted.
  c->whole = dir + "/data/C01-whole";
  const std::string& whole = c->whole;
  const test::CommandRun reference = test::runCommand(c->command(whole));
  ASSERT_EQ(reference.status, 0) << reference.out;
  c->expected = capture(reference.out, "volume checksum ([0-9a-f]{16})");
  ASSERT_FALSE(c->expected.empty()) << reference.out;
  EXPECT_NE(reference.out.find("stage done"), std::string::npos) << reference.out;
  c->reference_counts = countJournal(whole + "/session.cbj");
  EXPECT_EQ(c->reference_counts.sample_times, c->source.sample_times);
  EXPECT_EQ(c->reference_counts.answers.size(), 3u);
  c->answers = readText(whole + "/questionnaire.csv");
  EXPECT_EQ(c->answers, "participant,Q1,Q2,Q3\nC01,4,2,5\n");
  // A run resuming the completed session whose pen never connects keeps the pen an earlier run
  // recorded in session.json (it wrote null there once: a last restart that ended before its
  // pen connected).
  {
    const test::CommandRun penless = test::runCommand(
        std::string(CB_CLOUDBRUSH_BIN) + " study run " + protocol_path +
        " --display surfaceless --size " + std::to_string(kW) + "x" + std::to_string(kH) +
        " --grid 64 --participant 1 --backend none --end-seconds 0.3 --seconds 90 --resume " +
        whole);
    ASSERT_EQ(penless.status, 0) << penless.out;
    const std::string json = readText(whole + "/session.json");
    EXPECT_NE(json.find("\"serial\": null, \"serial_note\": \"replay: "), std::string::npos)
        << json;
    EXPECT_NE(json.find("\"status\": \"completed\""), std::string::npos) << json;
  }
}

// When each kill lands (see the test), drawn from the seed in this order.
struct KillDraws {
  std::mt19937 random;
  std::uniform_int_distribution<int> delay_ms{0, 2500}, startup_ms{0, 300}, during_startup{0, 4};
};

struct KillTally {
  int killed = 0, resumes = 0, finished = 0;
};

// Kill `i`: the runner started on `folder`, killed; the journal lost and doubled nothing since
// `before` (then the journal's counts now).
void killOnce(const CrashRun& c, const std::string& folder, int i, KillDraws* draws,
              JournalCounts* before, KillTally* tally) {
  const std::string journal = folder + "/session.cbj";
  const std::string log = c.dir + "/run" + std::to_string(i) + ".log";
  const bool in_startup = draws->during_startup(draws->random) == 0;
  const int wait = in_startup ? draws->startup_ms(draws->random) : draws->delay_ms(draws->random);
  const pid_t pid = spawn(c.command(folder), log);
  ASSERT_GT(pid, 0);
  if (!in_startup)
    for (int t = 0; t < 3000; ++t) {  // at most 30 s
      const std::string so_far = readText(log);
      if (so_far.find("study.session ") != std::string::npos ||
          so_far.find("resumed ") != std::string::npos || exited(pid))
        break;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  std::this_thread::sleep_for(std::chrono::milliseconds(wait));
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  const std::string out = readText(log);
  if (WIFSIGNALED(status))
    ++tally->killed;
  else
    ++tally->finished;
  if (out.find("resumed ") != std::string::npos) ++tally->resumes;
  // A restart whose loop ran (the test waited for its first record) carried the session on.
  // (One killed while it starts may not have said so yet: how many are is the seed's draw.)
  if (i > 0 && !in_startup && !before->sample_times.empty()) {
    EXPECT_NE(out.find("resumed "), std::string::npos) << "kill " << i << " did not resume\n"
                                                       << out;
  }
  const JournalCounts now =
      std::filesystem::exists(journal) ? countJournal(journal) : JournalCounts{};
  std::printf("kill %2d %4d ms after %s: %s; %zu samples, %d strokes, %zu answers, stage %s\n", i,
              wait, in_startup ? "start" : "the loop ran",
              WIFSIGNALED(status) ? "killed" : "had finished", now.sample_times.size(), now.strokes,
              now.answers.size(), now.stages.empty() ? "-" : now.stages.back().c_str());
  EXPECT_TRUE(WIFSIGNALED(status) || WEXITSTATUS(status) == 0) << out;
  // Nothing recorded is lost, nothing is recorded twice: the journal's samples are always the
  // pen's first N, and its strokes and answers only grow.
  ASSERT_LE(now.sample_times.size(), c.source.sample_times.size());
  EXPECT_TRUE(
      std::equal(now.sample_times.begin(), now.sample_times.end(), c.source.sample_times.begin()))
      << "kill " << i << ": the journal's samples are not the pen's in order\n"
      << out;
  EXPECT_GE(now.sample_times.size(), before->sample_times.size()) << "kill " << i;
  EXPECT_GE(now.strokes, before->strokes) << "a completed stroke was lost at kill " << i;
  ASSERT_GE(now.answers.size(), before->answers.size()) << "an answer was lost at kill " << i;
  EXPECT_TRUE(std::equal(before->answers.begin(), before->answers.end(), now.answers.begin()))
      << "kill " << i;
  *before = now;
}

// The last run, uninterrupted, ends the session as the uninterrupted one ended.
void checkEndsAsTheWholeRun(const CrashRun& c, const std::string& folder) {
  const std::string journal = folder + "/session.cbj";
  const test::CommandRun last = test::runCommand(c.command(folder));
  ASSERT_EQ(last.status, 0) << last.out;
  EXPECT_NE(last.out.find("resumed "), std::string::npos) << last.out;
  EXPECT_NE(last.out.find("stage done"), std::string::npos) << last.out;
  EXPECT_EQ(capture(last.out, "volume checksum ([0-9a-f]{16})"), c.expected) << last.out;
  const JournalCounts final_counts = countJournal(journal);
  EXPECT_EQ(final_counts.sample_times, c.source.sample_times) << "every pen sample, once";
  EXPECT_EQ(final_counts.strokes, c.source.strokes);
  EXPECT_EQ(final_counts.stages, c.reference_counts.stages)
      << "the same stages, saved files and answers as the uninterrupted run";
  EXPECT_EQ(readText(folder + "/questionnaire.csv"), c.answers);
  for (const char* task : {"first", "second"})
    EXPECT_EQ(readText(folder + "/tasks/" + task + ".cbvol"),
              readText(c.whole + "/tasks/" + task + ".cbvol"))
        << "task " << task << "'s volume";
  const std::string json = readText(folder + "/session.json");
  EXPECT_NE(json.find("\"status\": \"completed\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"task:second\", \"questionnaire\""), std::string::npos) << json;
  // A recorded pen has no serial to report, and the offscreen display no refresh: both null,
  // each with the reason.
  EXPECT_NE(json.find("\"serial\": null, \"serial_note\": \"replay: "), std::string::npos) << json;
  EXPECT_NE(json.find("\"refresh_hz\": null, \"refresh_note\": \"surfaceless: "), std::string::npos)
      << json;
  const test::CommandRun replay =
      test::runCommand(std::string(CB_CLOUDBRUSH_BIN) + " replay " + journal);
  EXPECT_EQ(replay.status, 0) << replay.out;
  EXPECT_EQ(capture(replay.out, "volume checksum: ([0-9a-f]{16})"), c.expected) << replay.out;
}

TEST(StudyResumeCrash, KilledAtRandomTheSessionResumesAndEndsAsAnUninterruptedOne) {
  const auto started = std::chrono::steady_clock::now();
  CrashRun c;
  c.dir =
      (std::filesystem::temp_directory_path() / ("cb_study_crash_" + std::to_string(::getpid())))
          .string();
  const std::string& dir = c.dir;
  std::filesystem::remove_all(dir);
  ASSERT_NO_FATAL_FAILURE(runUninterrupted(&c));

  const unsigned seed = cb::test::testSeed("study crash test");
  const int kills = std::getenv("CB_CRASH_KILLS") ? std::atoi(std::getenv("CB_CRASH_KILLS")) : 20;
  std::printf("study crash test: %d kills\n", kills);
  // One kill in five lands while the runner starts (display, renderer, the journal's replay);
  // the others once its loop is about to run (it printed its first study record, or that it
  // resumed), 0–2.5 s on (each restart first runs its startup and the time since the last
  // record again).
  KillDraws draws{std::mt19937(seed)};
  const std::string folder = dir + "/data/C01-crashed";
  KillTally tally;
  JournalCounts before;
  for (int i = 0; i < kills; ++i)
    ASSERT_NO_FATAL_FAILURE(killOnce(c, folder, i, &draws, &before, &tally));
  EXPECT_GE(tally.killed, kills / 2) << "most runs should have been killed, not finished";

  ASSERT_NO_FATAL_FAILURE(checkEndsAsTheWholeRun(c, folder));
  std::printf("%d killed, %d had finished, %d resumed; final checksum %s; %.1f s in all\n",
              tally.killed, tally.finished, tally.resumes, c.expected.c_str(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
  if (!HasFailure()) std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cb
