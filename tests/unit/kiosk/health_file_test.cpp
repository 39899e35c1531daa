// The health file: JSON content, the tracker's figures on a manual clock, atomic replacement
// (a concurrent reader never sees a torn file), the write interval, clear errors.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "app/core/atomic_file.h"
#include "app/kiosk/disk_space.h"
#include "app/kiosk/health_file_writer.h"
#include "app/kiosk/health_status.h"
#include "app/kiosk/health_tracker.h"
#include "app/kiosk/kiosk_service.h"
#include "app/kiosk/metrics_text.h"

namespace cb {
namespace {

namespace fs = std::filesystem;

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct TempDir {
  fs::path path;
  TempDir() {
    char tmpl[] = "/tmp/cb-health-XXXXXX";
    path = ::mkdtemp(tmpl);
  }
  ~TempDir() { fs::remove_all(path); }
};

TEST(HealthStatusJson, AllFieldsWithEscapingAndNulls) {
  HealthStatus s;
  s.written_unix_s = 1700000000;
  s.uptime_s = 12.5;
  s.frames_per_second = 59.94;
  s.last_input_age_s = 3.25;
  s.device_state = "connected: \"Wacom\" Intuos4\n";
  s.disk_free_bytes = 1000;
  s.disk_total_bytes = 4000;
  s.last_error = "pen\x01lost";
  EXPECT_EQ(healthStatusJson(s),
            "{\"written_unix_s\":1700000000,\"uptime_s\":12.500,\"frames_per_second\":59.940,"
            "\"last_input_age_s\":3.250,\"device_state\":\"connected: \\\"Wacom\\\" Intuos4\\n\","
            "\"disk_free_bytes\":1000,\"disk_total_bytes\":4000,"
            "\"last_error\":\"pen\\u0001lost\",\"storage\":\"ok\",\"frames\":0,\"visits\":0,"
            "\"strokes\":0,\"gallery_saved\":0,\"saves_failed\":0,\"screen\":\"starting\"}\n");
  HealthStatus empty;
  empty.frames_per_second = std::numeric_limits<double>::quiet_NaN();
  const std::string json = healthStatusJson(empty);
  EXPECT_NE(json.find("\"frames_per_second\":null"), std::string::npos) << json;
  EXPECT_NE(json.find("\"last_input_age_s\":null"), std::string::npos) << json;
  EXPECT_NE(json.find("\"disk_free_bytes\":null"), std::string::npos) << json;
  EXPECT_NE(json.find("\"last_error\":null"), std::string::npos) << json;
}

TEST(HealthTracker, UptimeFrameRateAndLastInputFollowTheClock) {
  ManualClock clock(5'000'000'000);
  HealthTracker tracker(clock);
  HealthStatus s = tracker.snapshot(nullptr, 0);
  EXPECT_EQ(s.uptime_s, 0.0);
  EXPECT_EQ(s.last_input_age_s, std::nullopt);
  EXPECT_EQ(s.device_state, "unknown");

  for (int i = 0; i < 60; ++i) {  // 60 frames at 50 Hz over 1.2 s
    clock.advance(20'000'000);
    tracker.onFrame();
    if (i == 30) tracker.onInput();
  }
  tracker.setDeviceState("no tablet");
  tracker.setError("hidraw: permission denied");
  s = tracker.snapshot(nullptr, 77);
  EXPECT_NEAR(s.uptime_s, 1.2, 1e-9);
  EXPECT_NEAR(s.frames_per_second, 50.0, 1e-6);
  ASSERT_TRUE(s.last_input_age_s);
  EXPECT_NEAR(*s.last_input_age_s, 29 * 0.02, 1e-9);
  EXPECT_EQ(s.device_state, "no tablet");
  EXPECT_EQ(s.last_error, "hidraw: permission denied");
  EXPECT_EQ(s.written_unix_s, 77);

  clock.advance(5'000'000'000);  // the loop stopped drawing: the rate must not stay at 50
  EXPECT_EQ(tracker.snapshot(nullptr, 0).frames_per_second, 0.0);
}

TEST(AtomicFile, ReplacesContentAndLeavesNoTemporary) {
  TempDir dir;
  const std::string path = (dir.path / "health.json").string();
  std::string error;
  ASSERT_TRUE(writeFileAtomically(path, "first", &error)) << error;
  ASSERT_TRUE(writeFileAtomically(path, "second", &error)) << error;
  EXPECT_EQ(readFile(path), "second");
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir.path)) {
    ++files;
    EXPECT_EQ(entry.path().filename(), "health.json");
  }
  EXPECT_EQ(files, 1);
}

TEST(AtomicFile, ConcurrentReaderNeverSeesATornFile) {
  TempDir dir;
  const fs::path path = dir.path / "health.json";
  const std::string small = "{\"a\":1}\n";
  const std::string large = "{\"b\":\"" + std::string(256 * 1024, 'x') + "\"}\n";
  std::string error;
  ASSERT_TRUE(writeFileAtomically(path.string(), small, &error)) << error;
  std::atomic<bool> stop{false};
  std::atomic<int> torn{0}, reads{0};
  std::thread reader([&] {
    while (!stop) {
      const std::string seen = readFile(path);
      if (seen != small && seen != large) ++torn;
      ++reads;
    }
  });
  for (int i = 0; i < 200; ++i)
    ASSERT_TRUE(writeFileAtomically(path.string(), i % 2 ? small : large, &error)) << error;
  stop = true;
  reader.join();
  EXPECT_GT(reads.load(), 0);
  EXPECT_EQ(torn.load(), 0);
}

TEST(AtomicFile, MissingDirectoryIsAClearError) {
  std::string error;
  EXPECT_FALSE(writeFileAtomically("/nonexistent-dir/health.json", "x", &error));
  EXPECT_NE(error.find("/nonexistent-dir/health.json"), std::string::npos) << error;
  EXPECT_NE(error.find("No such file"), std::string::npos) << error;
}

TEST(DiskSpace, ReportsTheFileSystemAndNamesABadPath) {
  std::string error;
  auto space = diskSpaceAt("/tmp", &error);
  ASSERT_TRUE(space) << error;
  EXPECT_GT(space->total_bytes, 0u);
  EXPECT_LE(space->free_bytes, space->total_bytes);
  EXPECT_EQ(diskSpaceAt("/nonexistent-dir", &error), std::nullopt);
  EXPECT_NE(error.find("/nonexistent-dir: statvfs"), std::string::npos) << error;
}

TEST(HealthFileWriter, WritesUnderTheDataDirectoryAtMostOncePerInterval) {
  TempDir dir;
  const fs::path data = dir.path / "data";  // created by the writer
  ManualClock clock;
  HealthTracker tracker(clock);
  HealthFileWriter writer(data.string(), tracker, clock, 5'000'000'000, [] { return 1234; });
  EXPECT_EQ(writer.path(), (data / "health.json").string());
  std::string error;
  ASSERT_TRUE(writer.writeIfDue(&error)) << error;
  std::string first = readFile(data / "health.json");
  EXPECT_EQ(first.rfind("{\"written_unix_s\":1234,\"uptime_s\":0.000,", 0), 0u) << first;
  EXPECT_EQ(first.find("\"disk_free_bytes\":null"), std::string::npos) << first;

  clock.advance(4'000'000'000);
  tracker.setError("late frame");
  ASSERT_TRUE(writer.writeIfDue(&error)) << error;
  EXPECT_EQ(readFile(data / "health.json"), first);  // not due yet
  clock.advance(1'000'000'000);
  ASSERT_TRUE(writer.writeIfDue(&error)) << error;
  const std::string second = readFile(data / "health.json");
  EXPECT_NE(second.find("\"uptime_s\":5.000"), std::string::npos) << second;
  EXPECT_NE(second.find("\"last_error\":\"late frame\""), std::string::npos) << second;
}

TEST(HealthFileWriter, UnwritableDataDirectoryIsAClearError) {
  TempDir dir;
  const fs::path blocker = dir.path / "file";
  std::ofstream(blocker) << "not a directory";
  ManualClock clock;
  HealthTracker tracker(clock);
  HealthFileWriter writer((blocker / "data").string(), tracker, clock);
  std::string error;
  EXPECT_FALSE(writer.write(&error));
  EXPECT_NE(error.find((blocker / "data").string()), std::string::npos) << error;
}

// The value of the one sample of `name` (with its labels) in Prometheus text, or "" when absent.
std::string sampleOf(const std::string& text, const std::string& name_and_labels) {
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(name_and_labels + " ", 0) == 0) return line.substr(name_and_labels.size() + 1);
  return "";
}

TEST(MetricsText, PrometheusTextWithEveryFigureTypedAndLabelsEscaped) {
  HealthStatus s;
  s.written_unix_s = 1700000000;
  s.uptime_s = 3600.5;
  s.frames_per_second = 59.5;
  s.device_state = "libusb \"Wacom\"\nconnected";
  s.disk_free_bytes = 123456789;
  s.disk_total_bytes = 987654321;
  s.storage = "NOT SAVING: disk full";
  s.frames = 214200;
  s.counts = {12, 345, 10, 2, "visitor"};
  const std::string text = metricsText(s, "0.1");
  EXPECT_EQ(sampleOf(text, "cloudbrush_visits_total"), "12");
  EXPECT_EQ(sampleOf(text, "cloudbrush_strokes_total"), "345");
  EXPECT_EQ(sampleOf(text, "cloudbrush_gallery_saved_total"), "10");
  EXPECT_EQ(sampleOf(text, "cloudbrush_saves_failed_total"), "2");
  EXPECT_EQ(sampleOf(text, "cloudbrush_frames_total"), "214200");
  EXPECT_EQ(sampleOf(text, "cloudbrush_frames_per_second"), "59.5");
  EXPECT_EQ(sampleOf(text, "cloudbrush_last_input_age_seconds"), "NaN") << "no input yet";
  EXPECT_EQ(sampleOf(text, "cloudbrush_disk_free_bytes"), "123456789");
  EXPECT_EQ(sampleOf(text, "cloudbrush_storage_ok"), "0");
  EXPECT_EQ(sampleOf(text, "cloudbrush_screen_info{screen=\"visitor\"}"), "1");
  EXPECT_EQ(sampleOf(text, "cloudbrush_version_info{version=\"0.1\"}"), "1");
  EXPECT_EQ(sampleOf(text, "cloudbrush_device_info{state=\"libusb \\\"Wacom\\\"\\nconnected\"}"),
            "1")
      << text;
  // Every sample has its HELP and TYPE, counters end in _total.
  std::istringstream in(text);
  int samples = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("# ", 0) == 0) continue;
    ++samples;
    const std::string name = line.substr(0, line.find_first_of("{ "));
    EXPECT_NE(text.find("# HELP " + name + " "), std::string::npos) << name;
    EXPECT_NE(text.find("# TYPE " + name + " "), std::string::npos) << name;
    if (text.find("# TYPE " + name + " counter") != std::string::npos) {
      EXPECT_EQ(name.substr(name.size() - 6), "_total") << name;
    }
  }
  EXPECT_EQ(samples, 15);
  s.storage = "ok";
  s.last_input_age_s = 2.5;
  const std::string ok = metricsText(s, "0.1");
  EXPECT_EQ(sampleOf(ok, "cloudbrush_storage_ok"), "1");
  EXPECT_EQ(sampleOf(ok, "cloudbrush_last_input_age_seconds"), "2.5");
}

TEST(HealthFileWriter, MetricsFileBesideTheHealthFile) {
  TempDir dir;
  ManualClock clock;
  HealthTracker tracker(clock);
  tracker.setCounts({3, 40, 2, 1, "attract"});
  HealthFileWriter writer((dir.path / "data").string(), tracker, clock);
  writer.setMetricsDir((dir.path / "textfile").string());
  std::string error;
  EXPECT_FALSE(writer.write(&error)) << "the metrics folder does not exist";
  EXPECT_NE(error.find((dir.path / "textfile" / "cloudbrush.prom").string()), std::string::npos)
      << error;
  EXPECT_TRUE(fs::exists(dir.path / "data" / "health.json")) << "written all the same";
  fs::create_directories(dir.path / "textfile");
  ASSERT_TRUE(writer.write(&error)) << error;
  const std::string metrics = readFile(dir.path / "textfile" / "cloudbrush.prom");
  EXPECT_EQ(sampleOf(metrics, "cloudbrush_visits_total"), "3");
  EXPECT_EQ(sampleOf(metrics, "cloudbrush_saves_failed_total"), "1");
  EXPECT_NE(readFile(dir.path / "data" / "health.json").find("\"screen\":\"attract\""),
            std::string::npos);
}

// A health file that cannot be written is logged once when it starts failing and once when it
// works again, is health's last_error meanwhile, and is not retried at every frame.
TEST(KioskService, HealthFileFailureIsLoggedOnceAndRecovers) {
  TempDir dir;
  const fs::path data = dir.path / "data";
  std::ofstream(data.string()) << "a file where the data dir should be";
  ManualClock clock;
  std::vector<std::string> reports;
  KioskService service(SdNotifier(), std::nullopt, clock, data.string(), nullptr,
                       [&](const std::string& line) { reports.push_back(line); });
  for (int i = 0; i < 20; ++i) {
    service.onIteration(true);
    clock.advance(500'000'000);  // 10 s: two more attempts
  }
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_NE(reports[0].find("health file NOT WRITTEN: " + data.string()), std::string::npos)
      << reports[0];
  EXPECT_NE(service.health().snapshot(nullptr, 0).last_error.find("health file: "),
            std::string::npos);
  fs::remove(data);
  clock.advance(5'000'000'000);
  service.onIteration(true);
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_NE(reports[1].find("health file written again"), std::string::npos) << reports[1];
  EXPECT_NE(readFile(data / "health.json").find("\"last_error\":\"health file: "),
            std::string::npos)
      << "the last error stays until another one";
}

}  // namespace
}  // namespace cb
