// Test helper: plays systemd's side of sd_notify — binds a unix datagram socket (in a fresh
// temporary directory) and receives the notifications sent to it, with their arrival times.
#pragma once

#include <chrono>
#include <optional>
#include <string>

namespace cb::test {

class NotifySocketListener {
 public:
  NotifySocketListener();  // throws std::runtime_error when the socket cannot be bound
  ~NotifySocketListener();
  NotifySocketListener(const NotifySocketListener&) = delete;
  NotifySocketListener& operator=(const NotifySocketListener&) = delete;

  const std::string& path() const { return path_; }
  // The next datagram, or nullopt when none arrives within `timeout`.
  std::optional<std::string> receive(std::chrono::milliseconds timeout);

 private:
  std::string dir_;
  std::string path_;
  int fd_ = -1;
};

}  // namespace cb::test
