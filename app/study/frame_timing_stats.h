// A session's frame timing from its Frame records (drivers/core/journal_frame.h): pen sample →
// present latency (percentiles, histogram), frame intervals while the pen moves, missed
// refreshes (dropped frames) and how they moved across the session (by quarter of its time).
// What PsychoPy-style timing reports give per run, for `replay --stats` and `study report`.
#pragma once

#include <string>
#include <vector>

#include "drivers/core/journal_frame.h"

namespace cb {

struct Percentiles {
  size_t n = 0;
  double p50 = 0, p95 = 0, p99 = 0, max = 0;  // milliseconds
};
// Nearest-rank percentiles of `ms` (sorted on a copy); n = 0 when empty.
Percentiles percentilesOf(std::vector<double> ms);

struct FrameTimingStats {
  size_t frames = 0;
  size_t ink_frames = 0;      // frames first showing pen samples, lift frames aside
  size_t untimed_frames = 0;  // showing samples stamped on another clock (no latency)
  std::string source;  // how present times were taken (the first frame's, "mixed" if not all)
  double refresh_ms = 0;
  bool nominal_refresh = false;
  Percentiles sample_to_present;  // newest sample shown → present, ink frames
  Percentiles sample_to_ready;    // newest sample shown → frame ready
  Percentiles oldest_to_present;  // oldest sample first shown → present, ink frames
  Percentiles lift_to_present;    // lift frames: the stroke's last sample → its cloud shown
  Percentiles interval;           // present → present between consecutive ink frames
  Percentiles cpu;                // the loop thread's CPU time per frame
  size_t missed_frames = 0, skipped_refreshes = 0;
  // sample → present histogram, ink frames: counts per bin of kHistogramEdgesMs.
  std::vector<size_t> histogram;
  struct Quarter {
    Percentiles sample_to_present;
    size_t frames = 0, missed_frames = 0;
  };
  std::vector<Quarter> quarters;  // the session's time (first to last frame) in four
};

// Bin edges of the histogram in ms; the last bin is open ("≥ 100").
const std::vector<double>& histogramEdgesMs();

FrameTimingStats frameTimingStats(const std::vector<FrameRecord>& frames);
// Text lines, each prefixed by `indent`; says so when there are no Frame records.
std::string formatFrameTimingStats(const FrameTimingStats& stats, const std::string& indent);

}  // namespace cb
