#include "drivers/replay/replay_pen_source.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "drivers/core/pen_units.h"

namespace cb {
namespace {

std::string writeJournal(int samples) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("cb_replay_test_" + std::to_string(getpid()) + ".cbj"))
                               .string();
  JournalWriter w;
  EXPECT_TRUE(w.open(path)) << w.error();
  PenDeviceInfo d;
  d.usb_vendor = 0x056A;
  d.usb_product = 0x00B9;
  d.x_max = 44704;
  std::snprintf(d.name, sizeof d.name, "recorded Intuos4");
  const auto info = encodeDeviceInfo(d);
  w.append(JournalRecordType::kDevice, 0, info.data(), info.size());
  w.append(JournalRecordType::kMode, 0, "paint");
  for (int i = 0; i < samples; ++i) {
    PenSample s;
    s.t_ns = 1'000'000'000 + i * 5'000'000;  // 200 Hz
    s.x_raw = i;
    s.in_proximity = i + 1 < samples;
    w.appendPenSample(s);
  }
  w.close();
  return path;
}

TEST(ReplayPenSource, PlaysEverySampleInOrderAsFastAsPolled) {
  const std::string path = writeJournal(1000);
  ReplayOptions o;
  o.realtime = false;
  ReplayPenSource src(path, o);
  EXPECT_EQ(src.deviceInfo().usb_product, 0x00B9);
  EXPECT_STREQ(src.deviceInfo().name, "recorded Intuos4");
  std::vector<PenSample> got;
  while (src.connection() != PenConnection::kFinished) src.poll(0, got);
  ASSERT_EQ(got.size(), 1000u);
  for (size_t i = 0; i < got.size(); ++i) ASSERT_EQ(got[i].x_raw, static_cast<int32_t>(i));
  EXPECT_FALSE(got.back().in_proximity);
  std::filesystem::remove(path);
}

TEST(ReplayPenSource, RealtimePacingFollowsTheClock) {
  const std::string path = writeJournal(10);
  ManualClock clock(500);
  ReplayPenSource src(path, ReplayOptions{}, &clock);
  std::vector<PenSample> got;
  src.poll(0, got);
  EXPECT_EQ(got.size(), 1u) << "the first sample plays at once";
  clock.advance(12'000'000);  // 12 ms: samples at 5 and 10 ms are due
  src.poll(0, got);
  EXPECT_EQ(got.size(), 3u);
  clock.advance(1'000'000'000);
  src.poll(0, got);
  EXPECT_EQ(got.size(), 10u);
  EXPECT_EQ(src.connection(), PenConnection::kFinished);
  std::filesystem::remove(path);
}

TEST(ReplayPenSource, MissingFileIsAStateNotACrash) {
  ReplayPenSource src("/nonexistent/cb.cbj", ReplayOptions{});
  EXPECT_EQ(src.connection(), PenConnection::kFinished);
  EXPECT_NE(src.statusMessage().find("/nonexistent/cb.cbj"), std::string::npos);
  std::vector<PenSample> got;
  src.poll(0, got);
  EXPECT_TRUE(got.empty());
}

}  // namespace
}  // namespace cb
