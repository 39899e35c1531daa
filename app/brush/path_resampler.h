// Resamples the pen path at a fixed arc-length step so dab spacing depends on the distance the
// pen travelled, not on the tablet's report rate: a path reported at 100 Hz and at 400 Hz yields
// dabs at the same places. Pressure, tilt and time are interpolated linearly along each segment;
// pen speed is estimated per segment and smoothed with a fixed time constant. A pen pressed or
// tilted in place (pressure change ≥ 0.04 or tilt ≥ 3° since the last dab) adds a dab where it is.
#pragma once

#include <vector>

#include "app/brush/stroke_result.h"

namespace cb {

// One placement of the brush sample on the footprint.
struct Dab {
  glm::vec2 footprint_px{0.0f};
  float pressure = 0.0f;
  float tilt_x_deg = 0.0f, tilt_y_deg = 0.0f;
  float speed_px_s = 0.0f;
  int64_t t_ns = 0;
  float arc_px = 0.0f;       // distance along the path from the stroke's first dab
  float size_factor = 1.0f;  // the dab's diameter scale (billow_profile.h; set by the brush)
};

class PathResampler {
 public:
  PathResampler(float spacing_px, float speed_smoothing_ms);
  // Starts a path; the first point always gives a dab (a one-sample stroke is a dot).
  void begin(const StrokePoint& first, std::vector<Dab>* out);
  // Extends the path to `p`, appending the dabs that fall on the new segment.
  void add(const StrokePoint& p, std::vector<Dab>* out);
  float speed() const { return speed_; }

 private:
  float spacing_, tau_s_;
  StrokePoint last_{};
  Dab last_dab_{};
  float travelled_since_dab_ = 0.0f;
  float arc_ = 0.0f;  // path length up to last_
  float speed_ = 0.0f;
};

}  // namespace cb
