// Measures the evdev path's delivery delay: a uinput pen device is fed events from one thread
// while an EvdevPenSource polls it on another; for each sample, the time from the event's kernel
// timestamp (CLOCK_MONOTONIC) to its arrival in the consumer thread.
#pragma once

#include <string>
#include <vector>

namespace cb {

struct EvdevLatencyResult {
  bool ran = false;
  std::string error;              // why it could not run (e.g. /dev/uinput missing)
  std::vector<double> delay_us;   // kernel timestamp -> consumer thread, per sample
  std::vector<double> wakeup_us;  // baseline: a pipe write -> read between two threads
};

// Sends `samples` pen reports at `rate_hz`. Needs write access to /dev/uinput.
EvdevLatencyResult measureEvdevLatency(int samples, double rate_hz);

}  // namespace cb
