#include "app/kiosk/sd_notifier.h"

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstdlib>
#include <cstring>

namespace cb {

SdNotifier SdNotifier::fromEnvironment() {
  const char* path = std::getenv("NOTIFY_SOCKET");
  return SdNotifier(path ? std::string(path) : std::string());
}

bool SdNotifier::notify(std::string_view state, std::string* error) const {
  if (!enabled()) return true;
  auto fail = [&](const std::string& why) {
    if (error) *error = "sd_notify to '" + socket_path_ + "': " + why;
    return false;
  };
  if (socket_path_[0] != '/' && socket_path_[0] != '@')
    return fail("NOTIFY_SOCKET must be an absolute path or start with '@'");

  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (socket_path_.size() > sizeof(address.sun_path) - 1)
    return fail("path longer than " + std::to_string(sizeof(address.sun_path) - 1) + " bytes");
  std::memcpy(address.sun_path, socket_path_.data(), socket_path_.size());
  if (socket_path_[0] == '@') address.sun_path[0] = '\0';  // abstract namespace: no terminator
  const socklen_t length = static_cast<socklen_t>(
      offsetof(sockaddr_un, sun_path) + socket_path_.size() + (socket_path_[0] == '@' ? 0 : 1));

  const int fd = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return fail(std::string("socket: ") + std::strerror(errno));
  const ssize_t sent = ::sendto(fd, state.data(), state.size(), MSG_NOSIGNAL,
                                reinterpret_cast<const sockaddr*>(&address), length);
  const int send_errno = errno;
  ::close(fd);
  if (sent < 0) return fail(std::string("sendto: ") + std::strerror(send_errno));
  if (static_cast<size_t>(sent) != state.size()) return fail("short datagram");
  return true;
}

bool SdNotifier::status(std::string_view text, std::string* error) const {
  std::string state = "STATUS=";
  for (char c : text) state += (c == '\n' || c == '\r') ? ' ' : c;
  return notify(state, error);
}

}  // namespace cb
