// Per-stroke measures of a session's pen trace (the strokes.csv table). A stroke is a maximal run
// of samples whose tip bit (PenSample::buttons & kPenTip, as the device reported it) is set; it
// is measured on the raw samples, before calibration or smoothing, so an analyst can recompute
// every column from samples.csv.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/study/session_trace.h"

namespace cb {

struct StrokeMeasures {
  uint32_t index = 0;         // 0-based, in time order within the session
  size_t first_sample = 0;    // index into SessionTrace::samples
  size_t sample_count = 0;    // tip-down samples
  double start_s = 0.0;       // first tip-down sample, seconds after the session's first record
  double duration_s = 0.0;    // last minus first tip-down sample
  double path_length_mm = 0;  // sum of distances between consecutive tip-down samples
  double mean_pressure = 0;   // normalised 0..1
  double max_pressure = 0;
  // Mean angle of the pen from vertical in degrees, from tilt x/y via tiltToAzimuthAltitude
  // (calibration/tilt.h): 90 − altitude.
  double mean_tilt_deg = 0;
  std::optional<double> speed_mm_s;  // path length / duration; none for a one-sample stroke
  std::string brush;  // from the last "brush=" UI record before the stroke; "" when none
  std::string mode;   // from the last Mode record before the stroke; "" when none
  // Time the painter's mapping of this stroke took (the first StrokeMapped record after the
  // stroke began and before the next one began); none in journals without those records.
  std::optional<double> mapping_ms;
};

std::vector<StrokeMeasures> measureStrokes(const SessionTrace& trace);

}  // namespace cb
