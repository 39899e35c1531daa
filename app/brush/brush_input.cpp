#include "app/brush/brush_input.h"

#include <algorithm>
#include <cmath>

namespace cb {

bool sanitizeBrushInput(BrushInput* in, int width, int height, float margin, InputHistory* history,
                        InputStats* stats) {
  if (!std::isfinite(in->footprint_px.x) || !std::isfinite(in->footprint_px.y) ||
      !std::isfinite(in->pressure)) {
    ++stats->dropped_non_finite;
    return false;
  }
  if (in->pressure < 0.0f || in->pressure > 1.0f) {
    in->pressure = std::clamp(in->pressure, 0.0f, 1.0f);
    ++stats->clamped_pressure;
  }
  bool tilt_repaired = false;
  for (float* tilt : {&in->tilt_x_deg, &in->tilt_y_deg}) {
    if (!std::isfinite(*tilt)) {
      *tilt = history->has_previous
                  ? (tilt == &in->tilt_x_deg ? history->tilt_x_deg : history->tilt_y_deg)
                  : 0.0f;
      tilt_repaired = true;
    } else if (std::abs(*tilt) > 90.0f) {
      *tilt = std::clamp(*tilt, -90.0f, 90.0f);
      tilt_repaired = true;
    }
  }
  if (tilt_repaired) ++stats->repaired_tilt;
  glm::vec2 lo(-margin), hi(float(width) + margin, float(height) + margin);
  glm::vec2 p = glm::clamp(in->footprint_px, lo, hi);
  if (p != in->footprint_px) {
    in->footprint_px = p;
    ++stats->clamped_position;
  }
  if (history->has_previous && in->t_ns < history->t_ns) {
    in->t_ns = history->t_ns;
    ++stats->repaired_timestamp;
  }
  history->has_previous = true;
  history->tilt_x_deg = in->tilt_x_deg;
  history->tilt_y_deg = in->tilt_y_deg;
  history->t_ns = in->t_ns;
  ++stats->accepted;
  return true;
}

}  // namespace cb
