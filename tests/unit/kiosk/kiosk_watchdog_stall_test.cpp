// The kiosk's real frame loop (FrameLoop running KioskScreen over the painter, EGL surfaceless on
// llvmpipe, the bundled config and attract journal) with KioskService wired as `cloudbrush kiosk`
// wires it, on the monotonic clock, against a datagram socket the test binds as systemd would
// (NOTIFY_SOCKET) and a 1 s watchdog (pings every 0.5 s): READY once after the first frame,
// STATUS with it, WATCHDOG from the loop — and when one frame hangs for 2.5 s the pings stop for
// longer than the watchdog's timeout (systemd would kill and restart the service), then resume.
// The hang comes after three pings, however long the first frames took.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <mutex>
#include <thread>
#include <vector>

#include "app/kiosk/kiosk_service.h"
#include "app/shell/frame_loop.h"
#include "app/shell/kiosk/kiosk_screen.h"
#include "app/shell/painter/paint_loop.h"
#include "app/shell/painter/paint_screen.h"
#include "notify_socket_listener.h"
#include "tests/support/test_display.h"

namespace cb {
namespace {

namespace fs = std::filesystem;
using Clock_ = std::chrono::steady_clock;
const std::string kConfigDir = std::string(CB_SOURCE_DIR) + "/config";

TEST(KioskWatchdog, AHungFrameStopsThePingsForLongerThanTheTimeoutThenTheyResume) {
  const std::string data_dir =
      (fs::temp_directory_path() / ("cb_kiosk_stall_" + std::to_string(::getpid()))).string();
  fs::remove_all(data_dir);
  std::string error;
  std::unique_ptr<Display> display = test::openTestDisplay(320, 180, &error);
  ASSERT_TRUE(display) << error;
  VolumeRenderer renderer;
  ASSERT_TRUE(renderer.init(&error)) << error;

  test::NotifySocketListener systemd;
  struct Received {
    std::string message;
    Clock_::time_point at;
  };
  std::mutex mutex;
  std::vector<Received> received;
  std::atomic<bool> done{false};
  std::thread receiver([&] {
    while (!done.load())
      if (auto m = systemd.receive(std::chrono::milliseconds(50))) {
        std::lock_guard<std::mutex> lock(mutex);
        received.push_back({*m, Clock_::now()});
      }
  });

  const MonotonicClock clock;
  const WatchdogTimeout watchdog{1'000'000'000};  // WatchdogSec=1s: a ping every 0.5 s
  KioskService service(SdNotifier(systemd.path()), watchdog, clock, data_dir, nullptr,
                       [](const std::string& problem) { ADD_FAILURE() << problem; });
  KioskSetup setup;
  setup.config = loadKioskConfig(kConfigDir + "/kiosk.toml");
  setup.texts = KioskTexts::load(kConfigDir + "/kiosk/texts.toml", "en", {});
  setup.attract_journal = readJournal(kConfigDir + "/" + setup.config.attract_journal).records;
  setup.data_dir = data_dir;
  setup.config_dir = kConfigDir;
  setup.visitor_settings = {320, 180, 32};
  setup.on_status = [&service](const std::string& status) { service.onStatus(status); };
  setup.on_input = [&service]() { service.onInput(); };
  PaintLoopOptions paint_options;
  paint_options.visitor_mode = true;
  paint_options.orbit_degrees_per_second = 0.0f;
  paint_options.config_dir = kConfigDir;
  paint_options.state_dir = data_dir;
  paint_options.clock = &clock;
  const Volume demo{glm::ivec3(8)};
  PaintScreen paint(*display, renderer, demo, Light{}, paint_options);
  KioskScreen kiosk(*display, renderer, paint, nullptr, clock, std::move(setup));

  // Frames until three pings went out (the first frames compile shaders: seconds on a loaded
  // machine), one frame that hangs for 2.5 s, then 2 s more.
  const auto pings_so_far = [&]() {
    std::lock_guard<std::mutex> lock(mutex);
    return std::count_if(received.begin(), received.end(),
                         [](const Received& r) { return r.message == "WATCHDOG=1"; });
  };
  Clock_::time_point stall_begin{}, stall_end{};
  std::atomic<bool> stop{false};
  FrameLoopOptions options;
  options.max_seconds = 120.0;  // a safety net only
  options.stop = &stop;
  options.clock = &clock;
  options.each_iteration = [&](bool presented) {
    service.onIteration(presented);
    if (stall_end != Clock_::time_point{} && Clock_::now() - stall_end > std::chrono::seconds(2))
      stop.store(true);
  };
  options.after_draw = [&](const FrameContext&) {
    if (stall_begin == Clock_::time_point{} && pings_so_far() >= 3) {
      stall_begin = Clock_::now();
      std::this_thread::sleep_for(std::chrono::milliseconds(2500));  // a hung draw
      stall_end = Clock_::now();
    }
  };
  FrameLoop loop(*display, nullptr);
  FrameLoopResult result;
  ASSERT_TRUE(loop.run(kiosk, options, &result, &error)) << error;
  service.stopping();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  done.store(true);
  receiver.join();
  fs::remove_all(data_dir);

  ASSERT_NE(stall_begin, Clock_::time_point{}) << "the loop never reached the stall";
  long ready = 0, status = 0, stopping = 0;
  std::vector<Clock_::time_point> pings;
  for (const Received& r : received) {
    ready += r.message == "READY=1";
    status += r.message.rfind("STATUS=", 0) == 0;
    stopping += r.message == "STOPPING=1";
    if (r.message == "WATCHDOG=1") pings.push_back(r.at);
  }
  EXPECT_EQ(ready, 1);
  EXPECT_GE(status, 1) << "STATUS goes with READY";
  EXPECT_EQ(stopping, 1);
  const auto seconds = [](Clock_::duration d) { return std::chrono::duration<double>(d).count(); };
  double longest_before = 0.0, across = 0.0, longest_after = 0.0;
  long before = 0, after = 0;
  for (size_t i = 1; i < pings.size(); ++i) {
    const double gap = seconds(pings[i] - pings[i - 1]);
    if (pings[i] <= stall_begin)
      longest_before = std::max(longest_before, gap), ++before;
    else if (pings[i - 1] <= stall_begin && pings[i] >= stall_end)
      across = gap;
    else if (pings[i - 1] >= stall_end)
      longest_after = std::max(longest_after, gap), ++after;
  }
  std::printf(
      "watchdog pings: %zu; longest gap before the stall %.2f s, across the 2.5 s stall %.2f s, "
      "after it %.2f s (timeout 1 s)\n",
      pings.size(), longest_before, across, longest_after);
  EXPECT_GE(before, 2) << "pings every 0.5 s while the loop runs";
  EXPECT_GE(after, 1) << "the pings resume when the loop runs again";
  EXPECT_GT(across, 1.0) << "the hung frame stopped the pings for longer than the timeout";
  // Wall-clock gaps stretch on a loaded machine; the hang's gap is the one that stands out.
  EXPECT_GT(across, std::max(longest_before, longest_after) + 1.0);
}

}  // namespace
}  // namespace cb
