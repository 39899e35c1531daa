// SdNotifier against a real unix datagram socket bound by the test (systemd's side).
#include "app/kiosk/sd_notifier.h"

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>

#include "tests/unit/kiosk/notify_socket_listener.h"

namespace cb {
namespace {

using namespace std::chrono_literals;
using test::NotifySocketListener;

TEST(SdNotifier, SendsReadyStatusWatchdogAndStoppingAsSeparateDatagrams) {
  NotifySocketListener listener;
  SdNotifier notifier(listener.path());
  std::string error;
  ASSERT_TRUE(notifier.ready(&error)) << error;
  ASSERT_TRUE(notifier.status("attract loop, 60 fps", &error)) << error;
  ASSERT_TRUE(notifier.watchdog(&error)) << error;
  ASSERT_TRUE(notifier.stopping(&error)) << error;
  EXPECT_EQ(listener.receive(1s), "READY=1");
  EXPECT_EQ(listener.receive(1s), "STATUS=attract loop, 60 fps");
  EXPECT_EQ(listener.receive(1s), "WATCHDOG=1");
  EXPECT_EQ(listener.receive(1s), "STOPPING=1");
  EXPECT_EQ(listener.receive(50ms), std::nullopt);
}

TEST(SdNotifier, StatusNewlinesCannotInjectAssignments) {
  NotifySocketListener listener;
  SdNotifier notifier(listener.path());
  std::string error;
  ASSERT_TRUE(notifier.status("tablet lost\nREADY=1", &error)) << error;
  EXPECT_EQ(listener.receive(1s), "STATUS=tablet lost READY=1");
}

TEST(SdNotifier, ReadsTheSocketFromNotifySocketVariable) {
  NotifySocketListener listener;
  ::setenv("NOTIFY_SOCKET", listener.path().c_str(), 1);
  SdNotifier notifier = SdNotifier::fromEnvironment();
  ::unsetenv("NOTIFY_SOCKET");
  EXPECT_TRUE(notifier.enabled());
  std::string error;
  ASSERT_TRUE(notifier.ready(&error)) << error;
  EXPECT_EQ(listener.receive(1s), "READY=1");
}

TEST(SdNotifier, WithoutNotifySocketIsDisabledAndSucceedsSilently) {
  ::unsetenv("NOTIFY_SOCKET");
  SdNotifier notifier = SdNotifier::fromEnvironment();
  EXPECT_FALSE(notifier.enabled());
  std::string error;
  EXPECT_TRUE(notifier.ready(&error));
  EXPECT_TRUE(error.empty());
}

TEST(SdNotifier, SendsToAnAbstractNamespaceSocket) {
  const std::string name = "cb-notify-test-" + std::to_string(::getpid());
  const int fd = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  ASSERT_GE(fd, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::memcpy(address.sun_path + 1, name.data(), name.size());
  const socklen_t length =
      static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + 1 + name.size());
  ASSERT_EQ(::bind(fd, reinterpret_cast<const sockaddr*>(&address), length), 0);

  SdNotifier notifier("@" + name);
  std::string error;
  ASSERT_TRUE(notifier.ready(&error)) << error;
  char buffer[64] = {};
  timeval tv{1, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
  ::close(fd);
  EXPECT_EQ(std::string(buffer, n > 0 ? static_cast<size_t>(n) : 0), "READY=1");
}

TEST(SdNotifier, RelativePathIsAClearError) {
  SdNotifier notifier("run/notify");
  std::string error;
  EXPECT_FALSE(notifier.ready(&error));
  EXPECT_NE(error.find("run/notify"), std::string::npos) << error;
  EXPECT_NE(error.find("absolute path"), std::string::npos) << error;
}

TEST(SdNotifier, TooLongPathIsAClearError) {
  SdNotifier notifier("/" + std::string(200, 'x'));
  std::string error;
  EXPECT_FALSE(notifier.ready(&error));
  EXPECT_NE(error.find("longer than"), std::string::npos) << error;
}

TEST(SdNotifier, MissingSocketNamesThePathAndTheErrno) {
  SdNotifier notifier("/nonexistent-dir/notify");
  std::string error;
  EXPECT_FALSE(notifier.watchdog(&error));
  EXPECT_NE(error.find("/nonexistent-dir/notify"), std::string::npos) << error;
  EXPECT_NE(error.find("No such file"), std::string::npos) << error;
}

}  // namespace
}  // namespace cb
