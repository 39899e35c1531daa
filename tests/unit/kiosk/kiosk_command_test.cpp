// `cloudbrush kiosk` as the real binary on the surfaceless display with a replayed visitor's
// stroke, under a test-bound NOTIFY_SOCKET and WATCHDOG_USEC (systemd's side): it says READY
// after its first frame, pings the watchdog from its loop, writes health.json into its data
// dir, ignores Esc, q and operator keys (visitor mode), clears the sky after the idle time
// (countdown first) and says STOPPING at the end.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <thread>

#include "app/session/paint_session.h"
#include "app/session/synthetic_session.h"
#include "notify_socket_listener.h"

namespace cb {
namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(KioskCommand, ReadyWatchdogHealthVisitorModeAndIdleReset) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("cb_kiosk_" + std::to_string(::getpid())))
          .string();
  std::filesystem::create_directories(dir + "/data");
  const std::string pen = dir + "/pen.cbj";
  {
    PaintSession recorder({320, 180, 64}, BrushConfig{}, MappingConfig{});
    JournalWriter journal;
    ASSERT_TRUE(journal.open(pen));
    recorder.recordTo(&journal, 0);
    const PenDeviceInfo tablet = syntheticTablet(320, 180);
    recorder.setDevice(tablet, 0);
    for (const PenSample& s : syntheticPenSamples(referencePaintStrokes(320, 180)[0], tablet, 320,
                                                  180, 200.0, 1'000'000'000))
      recorder.feed(s);
  }
  test::NotifySocketListener systemd;
  const std::string command =
      "NOTIFY_SOCKET='" + systemd.path() + "' WATCHDOG_USEC=1000000 LIBGL_ALWAYS_SOFTWARE=1 '" +
      std::string(CB_CLOUDBRUSH_BIN) +
      "' kiosk --display surfaceless --size 320x180 --grid 64 --backend replay --journal '" + pen +
      "' --no-record --data-dir '" + dir + "/data' --idle-seconds 0.6 --warning-seconds 0.3 " +
      "--orbit 30 --seconds 4 --keys esc,q,5,ctrl+s >'" + dir + "/out' 2>'" + dir + "/err'";
  int status = -1;
  std::thread runner([&] { status = std::system(command.c_str()); });
  std::multiset<std::string> received;
  std::optional<std::string> message;
  while ((message = systemd.receive(std::chrono::milliseconds(20000)))) {
    received.insert(
        message->substr(0, message->find('=') + 1) +
        (message->rfind("STATUS=", 0) == 0 ? "" : message->substr(message->find('=') + 1)));
    if (*message == "STOPPING=1") break;
  }
  runner.join();
  const std::string out = slurp(dir + "/out"), err = slurp(dir + "/err");
  EXPECT_EQ(status, 0) << out << err;
  EXPECT_EQ(received.count("READY=1"), 1u) << err;
  EXPECT_GE(received.count("WATCHDOG=1"), 2u) << "pings every 0.5 s from the loop";
  EXPECT_EQ(received.count("STATUS="), 1u);
  EXPECT_EQ(received.count("STOPPING=1"), 1u);
  EXPECT_NE(out.find("(time limit)"), std::string::npos) << "Esc and q did not quit: " << out;
  EXPECT_NE(err.find("mode-light is for the operator"), std::string::npos) << err;
  EXPECT_NE(err.find("save is for the operator"), std::string::npos) << err;
  EXPECT_NE(err.find("idle reset"), std::string::npos) << err;
  EXPECT_NE(out.find(" 1 strokes mapped"), std::string::npos) << out;
  const std::string health = slurp(dir + "/data/health.json");
  EXPECT_NE(health.find("\"uptime"), std::string::npos) << health;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cb
