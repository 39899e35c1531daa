// `cloudbrush kiosk` as the real binary on the surfaceless display with a replayed visitor's
// stroke, under a test-bound NOTIFY_SOCKET and WATCHDOG_USEC (systemd's side): it says READY
// after its first frame, pings the watchdog from its loop, writes health.json into its data
// dir, ignores Esc, q and operator keys (visitor mode), clears the sky after the idle time
// (countdown first) and says STOPPING at the end. And a scripted visit (operator panel, a
// stroke, the gallery, the idle reset) under strace writes nothing outside its data dir.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <thread>

#include <sys/wait.h>

#include "app/session/paint_session.h"
#include "app/session/synthetic_session.h"
#include "notify_socket_listener.h"
#include "tests/support/strace_file_writes.h"

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
  EXPECT_GE(received.count("STATUS="), 2u) << "with READY, then the attract loop after the reset";
  EXPECT_EQ(received.count("STOPPING=1"), 1u);
  EXPECT_NE(out.find("(time limit)"), std::string::npos) << "Esc and q did not quit: " << out;
  EXPECT_NE(err.find("That key is for the operator / 该按键仅供操作员使用 (5)"), std::string::npos)
      << err;
  EXPECT_NE(err.find("That key is for the operator / 该按键仅供操作员使用 (Ctrl+S)"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("idle reset"), std::string::npos) << err;
  EXPECT_NE(out.find(" 1 strokes mapped"), std::string::npos) << out;
  const std::string health = slurp(dir + "/data/health.json");
  EXPECT_NE(health.find("\"uptime"), std::string::npos) << health;
  std::filesystem::remove_all(dir);
}

// Every file under `root` except `skip`, with its size and modification time.
std::map<std::string, std::string> snapshot(const std::string& root, const std::string& skip) {
  std::map<std::string, std::string> files;
  for (auto it = std::filesystem::recursive_directory_iterator(root);
       it != std::filesystem::recursive_directory_iterator(); ++it) {
    const std::string path = it->path().string();
    if (path == skip) {
      it.disable_recursion_pending();
      continue;
    }
    std::error_code ec;
    const auto size = it->is_regular_file(ec) ? it->file_size(ec) : 0;
    files[path] = std::to_string(size) + "@" +
                  std::to_string(it->last_write_time(ec).time_since_epoch().count());
  }
  return files;
}

void writeVisitorJournal(const std::string& path) {
  PaintSession recorder({320, 180, 64}, BrushConfig{}, MappingConfig{});
  JournalWriter journal;
  ASSERT_TRUE(journal.open(path));
  recorder.recordTo(&journal, 0);
  const PenDeviceInfo tablet = syntheticTablet(320, 180);
  recorder.setDevice(tablet, 0);
  for (const PenSample& s : syntheticPenSamples(referencePaintStrokes(320, 180)[0], tablet, 320,
                                                180, 200.0, 1'000'000'000))
    recorder.feed(s);
}

TEST(KioskCommand, OperatorShutdownExitsWithTheStatusTheUnitDoesNotRestart) {
  const std::string data =
      (std::filesystem::temp_directory_path() / ("cb_kiosk_off_" + std::to_string(::getpid())))
          .string();
  std::filesystem::remove_all(data);
  // The PIN set beforehand (no default one), as the installer does.
  const std::string set_pin = "echo 2468 | '" + std::string(CB_CLOUDBRUSH_BIN) +
                              "' kiosk --set-pin --data-dir '" + data + "'";
  ASSERT_EQ(std::system(set_pin.c_str()), 0);
  // The combination, the PIN, X and Y: the panel shuts the kiosk down.
  const std::string command = "LIBGL_ALWAYS_SOFTWARE=1 '" + std::string(CB_CLOUDBRUSH_BIN) +
                              "' kiosk --display surfaceless --size 160x90 --grid 16 --backend "
                              "none --no-record --data-dir '" +
                              data + "' --seconds 60 --keys ctrl+alt+o,2,4,6,8,enter,x,y >'" +
                              data + ".out' 2>&1";
  const int status = std::system(command.c_str());
  const std::string out = slurp(data + ".out");
  ASSERT_TRUE(WIFEXITED(status)) << out;
  EXPECT_EQ(WEXITSTATUS(status), 10) << out;
  EXPECT_NE(out.find("(operator shutdown)"), std::string::npos) << out;
  const std::string log = slurp(data + "/operator.log");
  EXPECT_NE(log.find("Z panel-opened\n"), std::string::npos) << log;
  EXPECT_NE(log.find("Z shutdown\n"), std::string::npos) << log;
  std::filesystem::remove_all(data);
  std::filesystem::remove(data + ".out");
}

// --sync-udp is refused in kiosk mode with its reason (exit 2, before any window); a run without
// MESA_SHADER_CACHE_DIR (by hand, not under the unit) still keeps Mesa's shader cache in the data
// dir, as --help says of everything the kiosk writes (Mesa would use ~/.cache of the passwd entry).
TEST(KioskCommand, SyncUdpRefusedWithItsReasonAndMesaCacheInTheDataDir) {
  namespace fs = std::filesystem;
  const std::string data =
      (fs::temp_directory_path() / ("cb_kiosk_manual_" + std::to_string(::getpid()))).string();
  fs::remove_all(data);
  const std::string kiosk =
      "env -u MESA_SHADER_CACHE_DIR -u XDG_CACHE_HOME LIBGL_ALWAYS_SOFTWARE=1 '" +
      std::string(CB_CLOUDBRUSH_BIN) +
      "' kiosk --display surfaceless --size 160x90 --grid 16 --backend none "
      "--no-record --data-dir '" +
      data + "' --seconds 2 ";
  int status = std::system((kiosk + "--sync-udp 9999 >'" + data + ".out' 2>&1").c_str());
  std::string out = slurp(data + ".out");
  ASSERT_TRUE(WIFEXITED(status)) << out;
  EXPECT_EQ(WEXITSTATUS(status), 2) << out;
  EXPECT_NE(out.find("--sync-udp is not a kiosk option"), std::string::npos) << out;
  EXPECT_NE(out.find("allows no IP sockets"), std::string::npos) << out;
  status = std::system((kiosk + ">'" + data + ".out' 2>&1").c_str());
  out = slurp(data + ".out");
  ASSERT_TRUE(WIFEXITED(status)) << out;
  EXPECT_EQ(WEXITSTATUS(status), 0) << out;
  size_t cache_files = 0;
  std::error_code ec;
  for (const auto& e : fs::recursive_directory_iterator(data + "/mesa-shader-cache", ec))
    cache_files += e.is_regular_file();
  EXPECT_GT(cache_files, 0u) << "Mesa's shader cache under the data dir";
  fs::remove_all(data);
  fs::remove(data + ".out");
}

// Never a crash loop: a bad config file or an unusable data dir shows the error screen (logged,
// health.json's last_error) and the kiosk stays up until stopped (here --seconds), exiting with 3
// instead of 1 or 2 at once (under Restart=always a restart loop into a blank screen).
TEST(KioskCommand, BadConfigOrUnusableDataDirShowsTheErrorScreenInsteadOfExiting) {
  namespace fs = std::filesystem;
  const std::string root =
      (fs::temp_directory_path() / ("cb_kiosk_bad_" + std::to_string(::getpid()))).string();
  fs::remove_all(root);
  fs::create_directories(root);
  fs::copy(std::string(CB_SOURCE_DIR) + "/config", root + "/config", fs::copy_options::recursive);
  const auto run = [&](const std::string& data, double* seconds) {
    const auto start = std::chrono::steady_clock::now();
    const std::string command = "CLOUDBRUSH_CONFIG_DIR='" + root +
                                "/config' LIBGL_ALWAYS_SOFTWARE=1 '" + CB_CLOUDBRUSH_BIN +
                                "' kiosk --display surfaceless --size 160x90 --grid 16 "
                                "--backend none --no-record --data-dir '" +
                                data + "' --seconds 2 >'" + root + "/out' 2>&1";
    const int status = std::system(command.c_str());
    *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  };
  // kiosk.toml with a bad value on line 8 (and every other config file handled the same way).
  const std::string kiosk_toml = root + "/config/kiosk.toml";
  std::string text = slurp(kiosk_toml);
  text.replace(text.find("idle_seconds = 90"), 17, "idle_seconds = \"long\"");
  std::ofstream(kiosk_toml) << text;
  double seconds = 0.0;
  EXPECT_EQ(run(root + "/data", &seconds), 3) << slurp(root + "/out");
  EXPECT_GE(seconds, 2.0) << "it stayed up (the error screen), it did not exit at once";
  std::string out = slurp(root + "/out");
  EXPECT_NE(out.find("CANNOT START: " + kiosk_toml + ":8: visitor.idle_seconds: expected a number"),
            std::string::npos)
      << out;
  EXPECT_NE(slurp(root + "/data/health.json").find("\"last_error\":\"" + kiosk_toml + ":8: "),
            std::string::npos)
      << slurp(root + "/data/health.json");
  EXPECT_NE(slurp(root + "/data/health.json").find("\"screen\":\"error\""), std::string::npos);
  // A syntax error in render.toml: the same screen, naming its line.
  fs::copy_file(std::string(CB_SOURCE_DIR) + "/config/kiosk.toml", kiosk_toml,
                fs::copy_options::overwrite_existing);
  std::ofstream(root + "/config/render.toml", std::ios::app) << "\n[broken\n";
  EXPECT_EQ(run(root + "/data", &seconds), 3);
  out = slurp(root + "/out");
  EXPECT_NE(out.find("CANNOT START: " + root + "/config/render.toml:"), std::string::npos) << out;
  // A data dir the kiosk cannot use (a file in its place; as root, permissions would not stop it).
  fs::copy_file(std::string(CB_SOURCE_DIR) + "/config/render.toml", root + "/config/render.toml",
                fs::copy_options::overwrite_existing);
  std::ofstream(root + "/not-a-dir") << "x";
  EXPECT_EQ(run(root + "/not-a-dir", &seconds), 3);
  out = slurp(root + "/out");
  EXPECT_NE(out.find("CANNOT START: " + root + "/not-a-dir: "), std::string::npos) << out;
  fs::remove_all(root);
}

TEST(KioskCommand, AScriptedVisitWritesOnlyIntoTheDataDir) {
  namespace fs = std::filesystem;
  const std::string root =
      (fs::temp_directory_path() / ("cb_kiosk_confine_" + std::to_string(::getpid()))).string();
  fs::remove_all(root);
  for (const char* dir : {"/home", "/cwd", "/data", "/pen"}) fs::create_directories(root + dir);
  std::ofstream(root + "/home/.profile") << "# a home with something in it\n";
  writeVisitorJournal(root + "/pen/pen.cbj");
  const std::string data = root + "/data";
  const std::string set_pin = "echo 2468 | '" + std::string(CB_CLOUDBRUSH_BIN) +
                              "' kiosk --set-pin --data-dir '" + data + "'";
  ASSERT_EQ(std::system(set_pin.c_str()), 0);
  const auto before = snapshot(root, data);
  // As the unit runs it (HOME, MESA_SHADER_CACHE_DIR), no XDG or state-dir variables, the
  // working directory elsewhere; the operator opens the panel and exports, a visitor paints,
  // the idle reset keeps the cloud in the gallery. The idle time leaves room for the first
  // frames, slow on a cold shader cache (seconds on llvmpipe).
  const std::string command =
      "cd '" + root + "/cwd' && env -u XDG_STATE_HOME -u XDG_CACHE_HOME -u XDG_CONFIG_HOME " +
      "-u XDG_DATA_HOME -u CLOUDBRUSH_STATE_DIR -u NOTIFY_SOCKET -u WATCHDOG_USEC HOME='" + root +
      "/home' MESA_SHADER_CACHE_DIR='" + data + "/mesa-shader-cache' LIBGL_ALWAYS_SOFTWARE=1 " +
      "strace -f -qq --seccomp-bpf -e trace=%file -o '" + root + "/strace.txt' '" +
      CB_CLOUDBRUSH_BIN +
      "' kiosk --display surfaceless --size 320x180 --grid 64 --backend replay --journal '" + root +
      "/pen/pen.cbj' --data-dir '" + data + "' --gallery on --idle-seconds 3 " +
      "--warning-seconds 1 --seconds 12 --keys ctrl+alt+o,2,4,6,8,enter,e,esc >'" + root +
      "/out' 2>&1";
  const int status = std::system(command.c_str());
  const std::string out = slurp(root + "/out");
  ASSERT_EQ(status, 0) << out;
  EXPECT_NE(out.find("idle reset"), std::string::npos) << out;
  // The data dir holds what the visit left ...
  EXPECT_TRUE(fs::exists(data + "/gallery/000001/thumbnail.png")) << out;
  EXPECT_TRUE(fs::exists(data + "/operator.log"));
  EXPECT_TRUE(fs::exists(data + "/health.json"));
  size_t journals = 0;
  for (const auto& entry : fs::directory_iterator(data + "/sessions"))
    journals += entry.path().extension() == ".cbj";
  EXPECT_GE(journals, 1u);
  // ... and nothing else under the home, the working directory or beside them changed.
  auto after = snapshot(root, data);
  after.erase(root + "/out");
  after.erase(root + "/strace.txt");
  EXPECT_EQ(after, before);
  // Every path the process (and its threads) opened for writing, created, renamed or removed
  // is inside the data dir (devices aside: the render node is opened read-write).
  const test::FileWrites writes =
      test::fileWritesOutside(slurp(root + "/strace.txt"), root + "/cwd", {data, root + "/out"});
  EXPECT_GT(writes.writes, 5u) << "strace saw the kiosk write its files";
  EXPECT_TRUE(writes.outside.empty()) << writes.outside.front();
  fs::remove_all(root);
}

}  // namespace
}  // namespace cb
