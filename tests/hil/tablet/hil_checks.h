// What every phase of the virtual tablet test shares: the "CB-HIL CHECK ok|FAIL" line the host
// script counts (Checker keeps the phase's failures), the monotonic clock, and waiting for a pen
// source to find its device.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "drivers/core/clock.h"
#include "drivers/core/pen_source.h"

namespace cb::hil {

inline int64_t nowNs() {
  return MonotonicClock().nowNs();
}

struct Checker {
  int failures = 0;
  bool operator()(bool ok, const std::string& what) {
    std::printf("CB-HIL CHECK %s %s\n", ok ? "ok" : "FAIL", what.c_str());
    std::fflush(stdout);
    if (!ok) ++failures;
    return ok;
  }
};

// Polls `src` until it is connected (true, with how long it took in *took_ns if asked) or
// `timeout_ms` passed (false).
inline bool waitConnected(PenSource& src, int timeout_ms, int64_t* took_ns = nullptr) {
  const int64_t start = nowNs();
  std::vector<PenSample> ignored;
  while (src.connection() != PenConnection::kConnected) {
    if (nowNs() - start > int64_t{timeout_ms} * 1000000) return false;
    src.poll(20, ignored);
  }
  if (took_ns) *took_ns = nowNs() - start;
  return true;
}

}  // namespace cb::hil
