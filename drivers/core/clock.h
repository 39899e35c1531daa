// Injectable monotonic clock: production code reads time through this so tests and replays can
// drive it by hand.
#pragma once

#include <cstdint>

namespace cb {

class Clock {
 public:
  virtual ~Clock() = default;
  virtual int64_t nowNs() const = 0;  // monotonic nanoseconds
};

// CLOCK_MONOTONIC, the same clock evdev timestamps use after EVIOCSCLOCKID.
class MonotonicClock final : public Clock {
 public:
  int64_t nowNs() const override;
};

// A clock that moves only when told to (tests, replay).
class ManualClock final : public Clock {
 public:
  explicit ManualClock(int64_t start_ns = 0) : now_ns_(start_ns) {}
  int64_t nowNs() const override { return now_ns_; }
  void set(int64_t ns) { now_ns_ = ns; }
  void advance(int64_t ns) { now_ns_ += ns; }

 private:
  int64_t now_ns_;
};

}  // namespace cb
