// One short study session recorded by the real runner (tests/support/short_study.h, `study run
// --backend replay --sync-udp`), read three ways that must agree:
//   - strokes.csv's rows of kind "stroke" are the journal's mapped strokes (StrokeMapped), with
//     the painter's numbers, and their count per task is trials.csv's `strokes`; the runner's
//     form taps are rows of their own, kind menu_tap, with no stroke number.
//   - every UDP sync marker a receiver on loopback got is the journal's Sync record, and its
//     monotonic time is the time of the event it marks (the stage, closing, answer and session
//     markers, the StrokeMapped record of its stroke); its wall time is the wall clock at that
//     event: wall − mono is the same for every marker, and each datagram arrived soon after its
//     wall time (not after the task's files were saved).
//
// CB_KEEP_SESSION_DATA=DIR keeps the session and its exports there for looking.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include "app/study/protocol.h"
#include "app/study/study_marker_text.h"
#include "drivers/core/journal.h"
#include "drivers/core/journal_frame.h"
#include "drivers/core/journal_records.h"
#include "tests/support/command_run.h"
#include "tests/support/short_study.h"
#include "tests/support/file_text.h"

namespace cb {
namespace {

namespace fs = std::filesystem;
using Table = std::vector<std::vector<std::string>>;

using cb::test::readText;

// Rows of a CSV whose fields hold no quoted commas (the columns read here have none).
Table readCsv(const std::string& path) {
  Table rows;
  std::istringstream in(readText(path));
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    rows.emplace_back(1);
    for (char c : line) {
      if (c == ',')
        rows.back().emplace_back();
      else
        rows.back().back().push_back(c);
    }
  }
  return rows;
}

size_t column(const Table& t, const std::string& name) {
  for (size_t i = 0; i < t[0].size(); ++i)
    if (t[0][i] == name) return i;
  ADD_FAILURE() << "no column " << name;
  return 0;
}

// A datagram and the kernel's wall-clock time of its arrival (SO_TIMESTAMPNS).
struct Received {
  std::string text;
  int64_t arrived_unix_ns = 0;
};

// Collects datagrams on a loopback port until stopped.
class SyncReceiver {
 public:
  SyncReceiver() {
    fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    EXPECT_GE(fd_, 0);
    const int on = 1;
    EXPECT_EQ(::setsockopt(fd_, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof on), 0);
    const timeval timeout{0, 50'000};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    sockaddr_in at{};
    at.sin_family = AF_INET;
    at.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    EXPECT_EQ(::bind(fd_, reinterpret_cast<sockaddr*>(&at), sizeof at), 0);
    socklen_t len = sizeof at;
    EXPECT_EQ(::getsockname(fd_, reinterpret_cast<sockaddr*>(&at), &len), 0);
    port_ = ntohs(at.sin_port);
    thread_ = std::thread([this] { receive(); });
  }
  ~SyncReceiver() {
    stop();
    ::close(fd_);
  }
  int port() const { return port_; }
  std::vector<Received> stop() {
    if (thread_.joinable()) {
      stop_ = true;
      thread_.join();
    }
    return received_;
  }

 private:
  void receive() {
    char buffer[2048];
    char control[256];
    while (!stop_) {
      iovec io{buffer, sizeof buffer};
      msghdr msg{};
      msg.msg_iov = &io;
      msg.msg_iovlen = 1;
      msg.msg_control = control;
      msg.msg_controllen = sizeof control;
      const ssize_t n = ::recvmsg(fd_, &msg, 0);
      if (n <= 0) continue;
      Received r;
      r.text.assign(buffer, size_t(n));
      for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c; c = CMSG_NXTHDR(&msg, c))
        if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_TIMESTAMPNS) {
          timespec ts{};
          std::memcpy(&ts, CMSG_DATA(c), sizeof ts);
          r.arrived_unix_ns = int64_t(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
        }
      received_.push_back(r);
    }
  }
  int fd_ = -1, port_ = 0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  std::vector<Received> received_;
};

class SessionData : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const char* keep = std::getenv("CB_KEEP_SESSION_DATA");
    dir_ = keep ? std::string(keep)
                : (fs::temp_directory_path() / ("cb_session_data_" + std::to_string(::getpid())))
                      .string();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    fs::copy(std::string(CB_SOURCE_DIR) + "/config/study/images", dir_ + "/images");
    const std::string protocol_path = dir_ + "/short.toml";
    std::ofstream(protocol_path) << test::kShortStudyProtocol;
    const StudyProtocol protocol = loadStudyProtocol(protocol_path);
    const std::string pen = dir_ + "/pen.cbj";
    test::recordShortStudyPen(protocol, pen);
    SyncReceiver receiver;
    run_ = test::runCommand(
        std::string(CB_CLOUDBRUSH_BIN) + " study run " + protocol_path +
        " --display surfaceless --size " + std::to_string(test::kShortStudyWidth) + "x" +
        std::to_string(test::kShortStudyHeight) +
        " --grid 32 --participant 1 --backend replay --journal " + pen +
        " --end-seconds 0.3 --seconds 90 --sync-udp 127.0.0.1:" + std::to_string(receiver.port()) +
        " --data-dir " + dir_ + "/data");
    // The last datagrams are on their way when the runner exits.
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    received_ = receiver.stop();
    const size_t at = run_.out.find("session folder: ");
    if (at == std::string::npos) return;
    journal_ = run_.out.substr(at + 16, run_.out.find('\n', at) - at - 16) + "/session.cbj";
    exported_ = test::runCommand(std::string(CB_CLOUDBRUSH_BIN) + " study export " + journal_ +
                                 " --out " + dir_ + "/csv");
  }
  static void TearDownTestSuite() {
    if (!std::getenv("CB_KEEP_SESSION_DATA")) fs::remove_all(dir_);
  }
  void SetUp() override {
    ASSERT_EQ(run_.status, 0) << run_.out;
    ASSERT_FALSE(journal_.empty()) << run_.out;
    ASSERT_EQ(exported_.status, 0) << exported_.out;
  }
  static std::string dir_, journal_;
  static test::CommandRun run_, exported_;
  static std::vector<Received> received_;
};
std::string SessionData::dir_, SessionData::journal_;
test::CommandRun SessionData::run_, SessionData::exported_;
std::vector<Received> SessionData::received_;

TEST_F(SessionData, StrokeRowsAreTheJournalsMappedStrokesAndTrialsCountThem) {
  // The journal's mapped strokes and the task each was mapped in.
  std::vector<uint32_t> mapped;
  for (const JournalRecord& r : readJournal(journal_).records)
    if (r.type == JournalRecordType::kStrokeMapped) {
      const std::optional<StrokeMappedRecord> m = parseStrokeMapped(r.text());
      ASSERT_TRUE(m.has_value()) << r.text();
      mapped.push_back(m->stroke);
    }
  ASSERT_GE(mapped.size(), 2u) << "the pen paints one stroke in each task";

  const Table strokes = readCsv(dir_ + "/csv/strokes.csv");
  const size_t kind = column(strokes, "kind"), stroke = column(strokes, "stroke"),
               task = column(strokes, "task"), gesture = column(strokes, "gesture");
  std::vector<uint32_t> stroke_rows;
  std::map<std::string, int> strokes_per_task;
  size_t menu_taps = 0;
  for (size_t i = 1; i < strokes.size(); ++i) {
    const std::vector<std::string>& row = strokes[i];
    EXPECT_EQ(row[gesture], std::to_string(i - 1)) << "gestures are numbered in order";
    if (row[kind] == "stroke") {
      ASSERT_NE(row[stroke], "NA");
      stroke_rows.push_back(uint32_t(std::stoul(row[stroke])));
      ++strokes_per_task[row[task]];
    } else {
      EXPECT_EQ(row[stroke], "NA") << "a " << row[kind] << " row has no stroke number";
      if (row[kind] == "menu_tap") ++menu_taps;
    }
  }
  EXPECT_EQ(stroke_rows, mapped) << "strokes.csv's strokes are the painter's, in order";
  // The consent, the code, the introduction and the three answers are pen taps on the forms.
  EXPECT_GE(menu_taps, 6u);

  const Table trials = readCsv(dir_ + "/csv/trials.csv");
  ASSERT_EQ(trials.size(), 3u) << "a header and the two tasks";
  const size_t trial_task = column(trials, "task"), trial_strokes = column(trials, "strokes");
  int in_trials = 0;
  for (size_t i = 1; i < trials.size(); ++i) {
    SCOPED_TRACE(trials[i][trial_task]);
    EXPECT_EQ(std::stoi(trials[i][trial_strokes]), strokes_per_task[trials[i][trial_task]]);
    EXPECT_GE(std::stoi(trials[i][trial_strokes]), 1);
    in_trials += std::stoi(trials[i][trial_strokes]);
  }
  EXPECT_EQ(size_t(in_trials), mapped.size()) << "every mapped stroke was in a task";

  // samples.csv: the samples of each stroke row carry its gesture and stroke numbers.
  const Table samples = readCsv(dir_ + "/csv/samples.csv");
  const size_t s_gesture = column(samples, "gesture"), s_stroke = column(samples, "stroke"),
               s_tip = column(samples, "tip");
  std::set<std::string> strokes_in_samples;
  for (size_t i = 1; i < samples.size(); ++i) {
    const std::vector<std::string>& row = samples[i];
    if (row[s_tip] == "1") {
      EXPECT_NE(row[s_gesture], "NA") << "sample " << i - 1;
    }
    if (row[s_stroke] == "NA") continue;
    strokes_in_samples.insert(row[s_stroke]);
    const std::vector<std::string>& gesture_row = strokes[size_t(std::stoul(row[s_gesture])) + 1];
    EXPECT_EQ(gesture_row[stroke], row[s_stroke]);
  }
  EXPECT_EQ(strokes_in_samples.size(), mapped.size());
}

// The journal time of each event a sync marker marks, keyed by the marker's kind and label.
std::map<std::string, int64_t> eventTimes(const JournalReadResult& journal) {
  std::map<std::string, int64_t> times;
  for (const JournalRecord& r : journal.records) {
    if (r.type == JournalRecordType::kStrokeMapped) {
      if (const std::optional<StrokeMappedRecord> m = parseStrokeMapped(r.text()))
        times["stroke_end " + std::to_string(m->stroke)] = r.t_ns;
      continue;
    }
    if (r.type != JournalRecordType::kMarker) continue;
    const std::string text(r.text());
    const size_t space = text.find(' ');
    const std::string event = text.substr(0, space), label = text.substr(space + 1);
    const bool task = label.rfind("stage=task ", 0) == 0;
    const std::map<std::string, std::string> kinds = {
        {"study.session", "session_start"},
        {"study.stage-begin", task ? "task_begin" : "stage_begin"},
        {"study.stage-closing", task ? "task_end" : "stage_closing"},
        {"study.stage-end", "stage_end"},
        {"study.answer", "answer"},
        {"study.consent", "consent"},
        {"study.end", "session_end"}};
    if (auto k = kinds.find(event); k != kinds.end()) times[k->second + " " + label] = r.t_ns;
  }
  return times;
}

TEST_F(SessionData, SyncMarkersCarryTheirEventsTimesAndArriveAtThem) {
  const JournalReadResult journal = readJournal(journal_);
  std::vector<std::string> journalled;
  for (const JournalRecord& r : journal.records)
    if (r.type == JournalRecordType::kSync) journalled.emplace_back(r.text());
  std::vector<std::string> texts;
  for (const Received& r : received_) texts.push_back(r.text);
  ASSERT_EQ(texts, journalled) << "every marker was sent once, as journalled";

  const std::map<std::string, int64_t> events = eventTimes(journal);
  std::map<std::string, int> kinds;
  std::optional<int64_t> offset;  // wall − mono of the first marker
  // Tolerance of a datagram's arrival after its wall time: the runner notices an event by the
  // frame after it at the latest (a form tap is timed at the frame it falls in; a pen sample is
  // read at the next frame) and sends the marker at once. While painting, the journal's Frame
  // records say when the next frame began (llvmpipe frames take tens to hundreds of ms on a
  // busy 2-core machine): the marker arrives by then, plus 50 ms for scheduling and delivery.
  // The forms' frames are not journalled: there the bound is 1 s (their frames took 45–340 ms
  // here under load, and 534 ms once beside the clang build of the sanitized fuzzers; the
  // markers of form events were not sent at all before, so any bound tells the two apart). Before markers were sent at their events, task boundaries arrived
  // 0.7–2.3 s late (after the task's files were saved), stroke ends 11–96 ms (after mapping).
  std::vector<int64_t> frame_begins;
  for (const JournalRecord& r : journal.records)
    if (r.type == JournalRecordType::kFrame)
      if (const std::optional<FrameRecord> f = decodeFrameRecord(r.t_ns, r.payload))
        frame_begins.push_back(f->begin_ns);
  ASSERT_GT(frame_begins.size(), 10u) << "the journal has its frames' timing";
  std::sort(frame_begins.begin(), frame_begins.end());
  const int64_t kSlackNs = 50'000'000, kFormFrameNs = 1'000'000'000;
  const auto toleranceNs = [&](int64_t event_ns) {
    const auto next = std::upper_bound(frame_begins.begin(), frame_begins.end(), event_ns);
    const bool painting = next != frame_begins.end() && next != frame_begins.begin() &&
                          *next - *std::prev(next) < 1'000'000'000;
    return painting ? *next - event_ns + kSlackNs : kFormFrameNs;
  };
  for (const Received& r : received_) {
    const std::optional<SyncMarker> m = parseSyncMarker(r.text);
    ASSERT_TRUE(m.has_value()) << r.text;
    ++kinds[m->kind];
    SCOPED_TRACE(r.text);
    std::printf("%-14s arrived %7.1f ms after its wall time (allowed %7.1f ms)\n", m->kind.c_str(),
                double(r.arrived_unix_ns - m->wall_ns) / 1e6,
                double(toleranceNs(m->mono_ns)) / 1e6);
    if (m->kind != "stroke_begin" && m->kind != "operator") {
      const auto event = events.find(m->kind + " " + m->label);
      ASSERT_NE(event, events.end()) << "no journal event for the marker";
      EXPECT_EQ(m->mono_ns, event->second) << "the marker's monotonic time is its event's";
    }
    // The same clock pair for every marker (one session clock; CLOCK_REALTIME and the
    // monotonic clock keep pace within microseconds over a 15 s session): wall is not taken
    // later than mono.
    if (!offset) offset = m->wall_ns - m->mono_ns;
    EXPECT_NEAR(double(m->wall_ns - m->mono_ns - *offset), 0.0, 1e6);
    ASSERT_GT(r.arrived_unix_ns, 0);
    EXPECT_GE(r.arrived_unix_ns - m->wall_ns, -1'000'000) << "arrived before its event";
    EXPECT_LE(r.arrived_unix_ns - m->wall_ns, toleranceNs(m->mono_ns)) << "arrived late";
  }
  for (const char* kind : {"session_start", "consent", "stage_begin", "task_begin", "task_end",
                           "stage_end", "answer", "stroke_begin", "stroke_end", "session_end"})
    EXPECT_GE(kinds[kind], 1) << kind;
  EXPECT_EQ(kinds["task_begin"], 2);
  EXPECT_EQ(kinds["task_end"], 2);
  EXPECT_GE(kinds["answer"], 3) << "the three Likert answers";
}

}  // namespace
}  // namespace cb
