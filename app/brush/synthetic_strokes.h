// Synthetic pen strokes for the brush tests, the brush benchmark and demos: a smooth path
// (Catmull-Rom through control points) traversed at a constant speed, with pressure and tilt as
// functions of the normalised arc length, sampled at any report rate. The same stroke at 100 Hz and
// 400 Hz traces the same curve.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "app/brush/brush_input.h"

namespace cb {

struct SyntheticStroke {
  std::string name;
  std::vector<glm::vec2> control_points;  // footprint pixels
  float speed_px_s = 300.0f;
  std::function<float(float)> pressure = [](float) { return 0.6f; };  // of arc fraction 0..1
  std::function<float(float)> tilt_x_deg = [](float) { return 0.0f; };
  std::function<float(float)> tilt_y_deg = [](float) { return 0.0f; };
};

// Samples at `rate_hz` from t = t0_ns, ending with a sample exactly at the path's end.
std::vector<BrushInput> sampleStroke(const SyntheticStroke& stroke, double rate_hz,
                                     int64_t t0_ns = 0);

// Fixed test strokes on a width × height footprint.
SyntheticStroke pressureRamp(int width, int height);  // left to right, pressure 0.05 -> 1
SyntheticStroke tiltSweep(int width, int height);     // left to right, tilt x -50° -> +50°
SyntheticStroke gentleCurve(int width, int height);   // an S curve, pressure swelling
// The eight basic strokes of 永 (thesis Fig. 5.1), in writing order, on a size × size footprint.
std::vector<SyntheticStroke> yongStrokes(int size);

}  // namespace cb
