// Sync markers for other recorders (video, eye trackers): task and stroke boundaries
// sent as one UDP datagram each, the text of drivers/core/journal_records.h's SyncMarker
// ("cloudbrush-sync v1 seq=… kind=… mono_ns=… wall_ns=… label=…"). Off unless a port is given
// (`cloudbrush paint --sync-udp [HOST:]PORT`); the same markers are always journalled (Sync
// records). Sending never blocks and never fails the session: a lost datagram is counted.
#pragma once

#include <cstdint>
#include <string>

namespace cb {

class SyncMarkerSender {
 public:
  SyncMarkerSender() = default;
  ~SyncMarkerSender();
  SyncMarkerSender(const SyncMarkerSender&) = delete;
  SyncMarkerSender& operator=(const SyncMarkerSender&) = delete;

  // "PORT" (localhost) or "HOST:PORT" with a numeric IPv4 host. False with *error naming what
  // was wrong.
  bool open(const std::string& where, std::string* error);
  bool isOpen() const { return fd_ >= 0; }
  void send(const std::string& datagram);
  uint64_t sent() const { return sent_; }
  uint64_t failed() const { return failed_; }

 private:
  int fd_ = -1;
  uint64_t sent_ = 0, failed_ = 0;
};

}  // namespace cb
