#include "drivers/core/clock.h"

#include <time.h>

namespace cb {

int64_t MonotonicClock::nowNs() const {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return int64_t(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

TimelineClock::TimelineClock(int64_t origin_ns)
    : origin_ns_(origin_ns), started_ns_(monotonic_.nowNs()) {}

}  // namespace cb
