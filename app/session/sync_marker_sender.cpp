#include "app/session/sync_marker_sender.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

namespace cb {

SyncMarkerSender::~SyncMarkerSender() {
  if (fd_ >= 0) ::close(fd_);
}

bool SyncMarkerSender::open(const std::string& where, std::string* error) {
  const size_t colon = where.rfind(':');
  const std::string host = colon == std::string::npos ? "127.0.0.1" : where.substr(0, colon);
  const std::string port_text = colon == std::string::npos ? where : where.substr(colon + 1);
  char* end = nullptr;
  const long port = std::strtol(port_text.c_str(), &end, 10);
  if (port_text.empty() || *end != '\0' || port < 1 || port > 65535) {
    *error = "sync markers: '" + where + "': expected PORT or HOST:PORT with a port in 1..65535";
    return false;
  }
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(uint16_t(port));
  if (::inet_pton(AF_INET, host.c_str(), &to.sin_addr) != 1) {
    *error = "sync markers: '" + host + "' is not a numeric IPv4 address";
    return false;
  }
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0 || ::connect(fd, reinterpret_cast<const sockaddr*>(&to), sizeof to) != 0) {
    *error = "sync markers: UDP to " + host + ":" + port_text + ": " + std::strerror(errno);
    if (fd >= 0) ::close(fd);
    return false;
  }
  if (fd_ >= 0) ::close(fd_);
  fd_ = fd;
  return true;
}

void SyncMarkerSender::send(const std::string& datagram) {
  if (fd_ < 0) return;
  if (::send(fd_, datagram.data(), datagram.size(), MSG_DONTWAIT | MSG_NOSIGNAL) ==
      ssize_t(datagram.size()))
    ++sent_;
  else
    ++failed_;  // nobody listening (ECONNREFUSED) or a full buffer: the journal still has it
}

}  // namespace cb
