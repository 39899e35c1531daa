#include "app/kiosk/watchdog_interval.h"

#include <gtest/gtest.h>

namespace cb {
namespace {

TEST(WatchdogInterval, UnsetMeansNoWatchdog) {
  std::string error;
  EXPECT_EQ(parseWatchdogTimeout(nullptr, nullptr, 42, &error), std::nullopt);
  EXPECT_TRUE(error.empty());
}

TEST(WatchdogInterval, PingsAtHalfTheTimeout) {
  std::string error;
  auto timeout = parseWatchdogTimeout("10000000", nullptr, 42, &error);
  ASSERT_TRUE(timeout) << error;
  EXPECT_EQ(timeout->timeout_ns, 10'000'000'000);
  EXPECT_EQ(timeout->pingIntervalNs(), 5'000'000'000);
}

TEST(WatchdogInterval, PidOfThisProcessIsAccepted) {
  std::string error;
  EXPECT_TRUE(parseWatchdogTimeout("2000000", "42", 42, &error)) << error;
}

TEST(WatchdogInterval, PidOfAnotherProcessMeansNoWatchdogForUs) {
  std::string error;
  EXPECT_EQ(parseWatchdogTimeout("2000000", "41", 42, &error), std::nullopt);
  EXPECT_TRUE(error.empty());
}

TEST(WatchdogInterval, BadValuesAreClearErrors) {
  for (const char* bad : {"", "abc", "0", "-5", "12s", "99999999999999999999"}) {
    std::string error;
    EXPECT_EQ(parseWatchdogTimeout(bad, nullptr, 42, &error), std::nullopt) << bad;
    EXPECT_NE(error.find("WATCHDOG_USEC='" + std::string(bad) + "'"), std::string::npos) << error;
  }
  std::string error;
  EXPECT_EQ(parseWatchdogTimeout("1000", "pid", 42, &error), std::nullopt);
  EXPECT_NE(error.find("WATCHDOG_PID='pid'"), std::string::npos) << error;
}

}  // namespace
}  // namespace cb
