// WatchdogPinger: pings at half the timeout on the injected clock; a loop that stops ticking
// stops the pings (what makes systemd restart a hung kiosk). Against a real NOTIFY_SOCKET.
#include "app/kiosk/watchdog_pinger.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <thread>
#include <vector>

#include "tests/unit/kiosk/notify_socket_listener.h"

namespace cb {
namespace {

using namespace std::chrono_literals;
using test::NotifySocketListener;

TEST(WatchdogPinger, PingsOncePerIntervalOnTheInjectedClock) {
  NotifySocketListener listener;
  SdNotifier notifier(listener.path());
  ManualClock clock(1'000);
  WatchdogPinger pinger(notifier, clock, WatchdogTimeout{10'000'000});  // 10 ms: ping every 5 ms
  EXPECT_EQ(pinger.pingIntervalNs(), 5'000'000);
  std::string error;

  ASSERT_TRUE(pinger.tick(&error)) << error;  // the first tick pings
  EXPECT_EQ(listener.receive(1s), "WATCHDOG=1");
  for (int frame = 1; frame < 5; ++frame) {  // 1..4 ms: not due
    clock.advance(1'000'000);
    ASSERT_TRUE(pinger.tick(&error)) << error;
  }
  EXPECT_EQ(listener.receive(20ms), std::nullopt);
  clock.advance(999'999);  // 4.999999 ms since the ping
  ASSERT_TRUE(pinger.tick(&error));
  EXPECT_EQ(listener.receive(20ms), std::nullopt);
  clock.advance(1);  // exactly 5 ms
  ASSERT_TRUE(pinger.tick(&error));
  EXPECT_EQ(listener.receive(1s), "WATCHDOG=1");
  EXPECT_EQ(pinger.pingsSent(), 2);
}

TEST(WatchdogPinger, UnsendablePingIsReportedAndRetriedOnTheNextTick) {
  ManualClock clock;
  SdNotifier broken("/nonexistent-dir/notify");
  WatchdogPinger pinger(broken, clock, WatchdogTimeout{10'000'000});
  std::string error;
  EXPECT_FALSE(pinger.tick(&error));
  EXPECT_NE(error.find("/nonexistent-dir/notify"), std::string::npos) << error;
  EXPECT_EQ(pinger.pingsSent(), 0);
  error.clear();
  EXPECT_FALSE(pinger.tick(&error));  // still due: tries again at once
  EXPECT_FALSE(error.empty());
}

// A frame loop on its own thread, on the real monotonic clock, with the watchdog configured the
// way systemd does it (environment variables). It runs, hangs for longer than WatchdogSec, then
// runs again. The listener must see regular pings, then silence longer than the timeout.
TEST(WatchdogPinger, StalledFrameLoopStopsThePings) {
  NotifySocketListener listener;
  const auto timeout = 400ms;  // WatchdogSec=0.4: pings every 200 ms
  ::setenv("NOTIFY_SOCKET", listener.path().c_str(), 1);
  ::setenv("WATCHDOG_USEC", std::to_string(timeout.count() * 1000).c_str(), 1);
  ::setenv("WATCHDOG_PID", std::to_string(::getpid()).c_str(), 1);
  std::string error;
  const SdNotifier notifier = SdNotifier::fromEnvironment();
  const std::optional<WatchdogTimeout> watchdog = watchdogTimeoutFromEnvironment(&error);
  ::unsetenv("NOTIFY_SOCKET");
  ::unsetenv("WATCHDOG_USEC");
  ::unsetenv("WATCHDOG_PID");
  ASSERT_TRUE(watchdog) << error;

  using Steady = std::chrono::steady_clock;
  std::atomic<bool> done{false};
  std::atomic<int64_t> stall_begin_ns{0}, stall_end_ns{0};
  auto nowNs = [] {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(Steady::now().time_since_epoch())
        .count();
  };
  std::thread loop([&] {
    MonotonicClock clock;
    WatchdogPinger pinger(notifier, clock, *watchdog);
    std::string tick_error;
    auto runFor = [&](std::chrono::milliseconds span) {
      const auto end = Steady::now() + span;
      while (Steady::now() < end) {
        pinger.tick(&tick_error);
        std::this_thread::sleep_for(5ms);  // one "frame"
      }
    };
    runFor(1000ms);
    stall_begin_ns = nowNs();
    std::this_thread::sleep_for(1200ms);  // the hang: no frames, no ticks
    stall_end_ns = nowNs();
    runFor(600ms);
    done = true;
  });

  std::vector<int64_t> arrivals;
  while (!done) {
    if (auto message = listener.receive(50ms)) {
      EXPECT_EQ(*message, "WATCHDOG=1");
      arrivals.push_back(nowNs());
    }
  }
  loop.join();
  while (auto message = listener.receive(20ms)) arrivals.push_back(nowNs());

  const int64_t timeout_ns = watchdog->timeout_ns;
  ASSERT_GE(arrivals.size(), 6u);
  int long_gaps = 0;
  for (size_t i = 1; i < arrivals.size(); ++i) {
    const int64_t gap = arrivals[i] - arrivals[i - 1];
    const bool spans_stall = arrivals[i - 1] <= stall_begin_ns && arrivals[i] >= stall_end_ns;
    if (spans_stall) {
      ++long_gaps;
      // systemd would have seen silence for longer than WatchdogSec= and restarted us.
      EXPECT_GT(gap, timeout_ns) << "gap " << gap / 1e6 << " ms";
      EXPECT_GE(gap, stall_end_ns - stall_begin_ns);
    } else {
      // While the loop runs, pings come at half the timeout: never late enough for a restart.
      EXPECT_LT(gap, timeout_ns) << "gap " << i << ": " << gap / 1e6 << " ms";
      EXPECT_GE(gap, watchdog->pingIntervalNs() - 50'000'000) << "pinged too often";
    }
  }
  EXPECT_EQ(long_gaps, 1);
  // Pings resumed after the hang.
  EXPECT_GT(arrivals.back(), stall_end_ns.load());
}

}  // namespace
}  // namespace cb
