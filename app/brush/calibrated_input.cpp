#include "app/brush/calibrated_input.h"

namespace cb {

BrushInput brushInputFromCalibrated(const MappedSample& s, float footprint_scale) {
  return brushInputFromCalibrated(s, glm::vec2(footprint_scale));
}

BrushInput brushInputFromCalibrated(const MappedSample& s, glm::vec2 footprint_scale) {
  BrushInput in;
  in.footprint_px = glm::vec2(float(s.x_px), float(s.y_px)) * footprint_scale;
  in.pressure = s.pressure;
  in.tilt_x_deg = s.tilt_x_deg;
  in.tilt_y_deg = s.tilt_y_deg;
  in.t_ns = s.t_ns;
  return in;
}

}  // namespace cb
