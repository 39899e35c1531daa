// The pen read on its own thread (drivers/core/threaded_pen_source.h): a caller that polls once
// per slow frame still gets every sample in order, and sees every unplug and replug as a
// connection state of its own. The backend here is a scripted PenSource (a tablet's timeline:
// connect, samples at 200 Hz, unplug, replug), because the host has no /dev/uinput; the real
// evdev path in the kernel is exercised by tests/hil/kms/kms_kiosk_test (label slow).
#include "drivers/core/threaded_pen_source.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "drivers/core/clock.h"

namespace cb {
namespace {

void sleepMs(int ms) {
  std::this_thread::sleep_for(std::chrono::milliseconds(ms));
}

// A tablet's timeline: a step per backend poll. Each step either connects (status names the
// device), disconnects (with the proximity-out sample an unplug gives), or emits one sample.
class ScriptedTablet final : public PenSource {
 public:
  struct Step {
    enum Kind { kConnect, kSample, kUnplug } kind;
    int device = 0;
  };
  explicit ScriptedTablet(std::vector<Step> steps) : steps_(std::move(steps)) {}
  const char* backendName() const override { return "scripted"; }
  void poll(int timeout_ms, std::vector<PenSample>& out) override {
    if (next_ >= steps_.size()) {
      sleepMs(timeout_ms > 0 ? timeout_ms : 0);
      return;
    }
    sleepMs(1);  // a report every few ms, as a tablet's
    const Step step = steps_[next_++];
    switch (step.kind) {
      case Step::kConnect:
        connection_ = PenConnection::kConnected;
        status_ = "reading device " + std::to_string(step.device);
        std::snprintf(info_.name, sizeof info_.name, "tablet %d", step.device);
        break;
      case Step::kSample: {
        PenSample s;
        s.t_ns = int64_t(++sequence_);
        s.in_proximity = true;
        out.push_back(s);
        break;
      }
      case Step::kUnplug: {
        PenSample s;
        s.t_ns = int64_t(++sequence_);
        s.in_proximity = false;
        out.push_back(s);
        connection_ = PenConnection::kSearching;
        status_ = "went away";
        break;
      }
    }
    polled_ = next_;
  }
  PenConnection connection() const override { return connection_; }
  const PenDeviceInfo& deviceInfo() const override { return info_; }
  std::string statusMessage() const override { return status_; }
  size_t stepsPlayed() const { return polled_; }

 private:
  std::vector<Step> steps_;
  size_t next_ = 0;
  std::atomic<size_t> polled_{0};
  uint64_t sequence_ = 0;
  PenConnection connection_ = PenConnection::kSearching;
  PenDeviceInfo info_{};
  std::string status_ = "searching";
};

using Step = ScriptedTablet::Step;

std::vector<Step> twoPlugs(int samples_each) {
  std::vector<Step> steps;
  for (int device = 1; device <= 2; ++device) {
    steps.push_back({Step::kConnect, device});
    for (int i = 0; i < samples_each; ++i) steps.push_back({Step::kSample, device});
    steps.push_back({Step::kUnplug, device});
  }
  return steps;
}

TEST(ThreadedPenSource, ASlowCallerGetsEverySampleAndEveryConnectionStateInOrder) {
  constexpr int kSamples = 150;
  auto backend = std::make_unique<ScriptedTablet>(twoPlugs(kSamples));
  const ScriptedTablet* tablet = backend.get();
  ThreadedPenSource pen(std::move(backend));
  EXPECT_EQ(pen.connection(), PenConnection::kSearching);
  EXPECT_STREQ(pen.backendName(), "scripted");
  // Frames of 150 ms while the tablet plays its whole timeline (≈ 2 × 152 steps of 1+ ms).
  std::vector<PenSample> all;
  std::vector<std::pair<PenConnection, std::string>> seen;  // each poll's state
  const int64_t start = MonotonicClock().nowNs();
  while (all.size() < 2u * (kSamples + 1) && MonotonicClock().nowNs() - start < 20'000'000'000) {
    sleepMs(150);
    std::vector<PenSample> got;
    pen.poll(0, got);
    all.insert(all.end(), got.begin(), got.end());
    seen.emplace_back(pen.connection(), pen.statusMessage());
  }
  EXPECT_EQ(tablet->stepsPlayed(), 2u * (kSamples + 2));
  ASSERT_EQ(all.size(), 2u * (kSamples + 1)) << "every sample, the unplugs' included";
  for (size_t i = 0; i < all.size(); ++i) EXPECT_EQ(all[i].t_ns, int64_t(i + 1)) << i;
  // The states the caller saw, consecutive repeats folded: device 1, gone, device 2, gone.
  std::vector<std::string> states;
  for (const auto& [connection, status] : seen) {
    const std::string s = std::string(penConnectionName(connection)) + ": " + status;
    if (states.empty() || states.back() != s) states.push_back(s);
  }
  EXPECT_EQ(states,
            (std::vector<std::string>{"connected: reading device 1", "searching: went away",
                                      "connected: reading device 2", "searching: went away"}));
  EXPECT_EQ(pen.droppedSamples(), 0u);
}

TEST(ThreadedPenSource, TheUnplugsProximityOutComesWithTheSearchingState) {
  ThreadedPenSource pen(std::make_unique<ScriptedTablet>(twoPlugs(3)));
  sleepMs(300);  // the whole timeline has played before the first poll
  std::vector<std::pair<PenConnection, std::vector<bool>>> polls;
  for (int i = 0; i < 6; ++i) {
    std::vector<PenSample> got;
    pen.poll(0, got);
    std::vector<bool> proximity;
    for (const PenSample& s : got) proximity.push_back(s.in_proximity);
    polls.emplace_back(pen.connection(), proximity);
  }
  using P = std::pair<PenConnection, std::vector<bool>>;
  EXPECT_EQ(polls, (std::vector<P>{{PenConnection::kConnected, {true, true, true}},
                                   {PenConnection::kSearching, {false}},
                                   {PenConnection::kConnected, {true, true, true}},
                                   {PenConnection::kSearching, {false}},
                                   {PenConnection::kSearching, {}},
                                   {PenConnection::kSearching, {}}}));
  EXPECT_STREQ(pen.deviceInfo().name, "tablet 2");
}

TEST(ThreadedPenSource, AWaitingPollReturnsAsSoonAsASampleArrives) {
  std::vector<Step> steps{{Step::kConnect, 1}, {Step::kSample, 1}};
  ThreadedPenSource pen(std::make_unique<ScriptedTablet>(steps));
  std::vector<PenSample> got;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < 10 && got.empty(); ++i) pen.poll(2000, got);
  const double waited =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(pen.connection(), PenConnection::kConnected);
  EXPECT_LT(waited, 1.5) << "poll(2000) returns on arrival, not at its timeout";
}

TEST(ThreadedPenSource, InputWaitingSaysWhetherAPollWouldBringNewsUntilItIsAllTaken) {
  ThreadedPenSource pen(std::make_unique<ScriptedTablet>(twoPlugs(2)));
  // The whole timeline queued (4 batches: connected, gone, connected, gone) before any poll.
  for (int i = 0; i < 200 && !pen.inputWaiting(); ++i) sleepMs(5);
  EXPECT_TRUE(pen.inputWaiting()) << "the first connection is news";
  sleepMs(300);
  int polls = 0;
  while (pen.inputWaiting() && polls < 10) {
    std::vector<PenSample> got;
    pen.poll(0, got);
    ++polls;
  }
  EXPECT_EQ(polls, 4) << "true until the poll that took the last queued state";
  EXPECT_FALSE(pen.inputWaiting());
  EXPECT_EQ(pen.connection(), PenConnection::kSearching);
  EXPECT_STREQ(pen.deviceInfo().name, "tablet 2");
}

TEST(ThreadedPenSource, AFullQueueDropsTheOldestSamplesAndCountsThem) {
  std::vector<Step> steps{{Step::kConnect, 1}};
  for (int i = 0; i < 100; ++i) steps.push_back({Step::kSample, 1});
  ThreadedPenSourceOptions options;
  options.max_queued_samples = 40;
  auto backend = std::make_unique<ScriptedTablet>(steps);
  const ScriptedTablet* tablet = backend.get();
  ThreadedPenSource pen(std::move(backend), options);
  for (int i = 0; i < 200 && tablet->stepsPlayed() < steps.size(); ++i) sleepMs(10);
  sleepMs(50);
  std::vector<PenSample> got;
  pen.poll(0, got);
  ASSERT_EQ(got.size(), 40u);
  EXPECT_EQ(got.front().t_ns, 61) << "the newest 40 of 100 stay";
  EXPECT_EQ(got.back().t_ns, 100);
  EXPECT_EQ(pen.droppedSamples(), 60u);
}

}  // namespace
}  // namespace cb
