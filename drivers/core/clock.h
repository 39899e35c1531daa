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

// The monotonic clock's pace on another time line: it reads `origin_ns` when made and runs on
// from there at the monotonic rate. A session driven by a recording runs on the recording's own
// time line with it (`study run --backend replay`), so its frames, timers and records share the
// recorded pen samples' clock, and a resumed run carries on from the last record's time.
class TimelineClock final : public Clock {
 public:
  explicit TimelineClock(int64_t origin_ns);
  int64_t nowNs() const override { return origin_ns_ + (monotonic_.nowNs() - started_ns_); }

 private:
  MonotonicClock monotonic_;
  int64_t origin_ns_, started_ns_;
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
