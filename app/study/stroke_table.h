// Per-gesture measures of a session's pen trace (the strokes.csv table). Every maximal run of
// samples whose tip bit (PenSample::buttons & kPenTip, as the device reported it) is set is one
// or more rows, marked by what the painter made of it:
//   stroke    a stroke the painter mapped into the cloud; `stroke` is the painter's own index
//             (the journal's stroke_begin/stroke_end Sync and StrokeMapped records), so these
//             rows agree with the journal, the sync markers and trials.csv's stroke counts.
//             A run the painter cut into two strokes (pressure dropping below the contact
//             threshold and rising again) is two rows; the raw tip-down samples before the
//             painter's contact belong to the stroke.
//   erase     a drag in erase mode (rub-out or vacuum)
//   menu_tap  the pen on the on-screen UI (a menu, a form, the runner's targets): the journal's
//             `pen_capture=on`
//   camera, canvas, light   a drag in that mode
//   unmapped  a touch in paint mode that made no stroke (below the contact threshold, or held
//             down after a stroke ended by itself)
// Journals without stroke Sync records (written before them) number their paint-mode runs as
// strokes in order. Measures are taken on the raw tip-down samples, before calibration or
// smoothing, so an analyst can recompute every column from samples.csv.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/study/session_trace.h"

namespace cb {

struct StrokeMeasures {
  uint32_t index = 0;              // the row's gesture number, 0-based in time order
  std::string kind;                // stroke, erase, menu_tap, camera, canvas, light, unmapped
  std::optional<uint32_t> stroke;  // the painter's stroke index (kind "stroke" only)
  size_t first_sample = 0;         // index into SessionTrace::samples
  size_t sample_count = 0;         // tip-down samples
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
  // Time the painter's mapping of this stroke took (its StrokeMapped record); none for other
  // kinds and in journals without those records.
  std::optional<double> mapping_ms;
};

// Every gesture (row) of the session in time order.
std::vector<StrokeMeasures> measureStrokes(const SessionTrace& trace);

// The painter's stroke index of each sample (-1 outside mapped strokes) and the gesture row of
// each sample (-1 outside gestures), from measureStrokes' rows.
struct SampleGestures {
  std::vector<int64_t> gesture, stroke;
};
SampleGestures sampleGestures(const SessionTrace& trace, const std::vector<StrokeMeasures>& rows);

}  // namespace cb
