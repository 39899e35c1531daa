// systemd's service notification protocol (sd_notify(3)) without libsystemd: each state is one
// datagram ("READY=1", "WATCHDOG=1", "STATUS=…", newline-separated) sent to the unix datagram
// socket named by $NOTIFY_SOCKET (a path, or "@name" for the abstract namespace). When the
// variable is unset (not started by systemd, or Type= is not notify) the notifier is disabled and
// every call succeeds without sending anything.
#pragma once

#include <string>
#include <string_view>

namespace cb {

class SdNotifier {
 public:
  // Disabled: sends nothing.
  SdNotifier() = default;
  // Sends to `socket_path` ("/run/…" or "@abstract"). An empty path gives a disabled notifier.
  explicit SdNotifier(std::string socket_path) : socket_path_(std::move(socket_path)) {}
  // From $NOTIFY_SOCKET (disabled when unset or empty).
  static SdNotifier fromEnvironment();

  bool enabled() const { return !socket_path_.empty(); }
  const std::string& socketPath() const { return socket_path_; }

  // Sends `state` as one datagram. False with *error (naming the socket and the errno text) when
  // the path is malformed (not absolute, not "@…", or longer than a unix socket address holds)
  // or sending fails. A disabled notifier returns true.
  bool notify(std::string_view state, std::string* error) const;

  bool ready(std::string* error) const { return notify("READY=1", error); }
  bool watchdog(std::string* error) const { return notify("WATCHDOG=1", error); }
  bool stopping(std::string* error) const { return notify("STOPPING=1", error); }
  // STATUS=text; newlines in `text` become spaces (a newline would start another assignment).
  bool status(std::string_view text, std::string* error) const;

 private:
  std::string socket_path_;
};

}  // namespace cb
