// What a brush consumes: one pen sample already mapped into paint-view footprint pixels with a
// calibrated pressure (app/calibration produces these from PenSamples). Bad values are repaired
// or dropped here, and counted, so nothing non-finite reaches a footprint.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace cb {

struct BrushInput {
  glm::vec2 footprint_px{0.0f};  // position in footprint pixels, (0,0) = top-left
  float pressure = 0.0f;         // 0..1
  float tilt_x_deg = 0.0f;       // from vertical, +x to the right
  float tilt_y_deg = 0.0f;       // from vertical, +y towards the user (down the footprint)
  int64_t t_ns = 0;              // monotonic timestamp
};

// Counts of repaired and rejected input, per stroke engine (reported, never silent).
struct InputStats {
  uint64_t accepted = 0;
  uint64_t dropped_non_finite = 0;  // NaN/inf position or pressure: sample dropped
  uint64_t clamped_pressure = 0;    // pressure outside 0..1
  uint64_t repaired_tilt = 0;       // NaN/inf tilt (previous tilt used) or beyond ±90°
  uint64_t clamped_position = 0;    // far outside the footprint (pulled to its margin)
  uint64_t repaired_timestamp = 0;  // time going backwards (held at the previous time)

  uint64_t rejected() const { return dropped_non_finite; }
  uint64_t repaired() const {
    return clamped_pressure + repaired_tilt + clamped_position + repaired_timestamp;
  }
};

// The previous accepted sample, used to repair the next one.
struct InputHistory {
  bool has_previous = false;
  float tilt_x_deg = 0.0f, tilt_y_deg = 0.0f;
  int64_t t_ns = 0;
};

// Repairs `in` in place; returns false when it must be dropped. Positions are kept within
// `margin` pixels around a width × height footprint so a glitched sample cannot make the path
// resampler walk millions of pixels.
bool sanitizeBrushInput(BrushInput* in, int width, int height, float margin, InputHistory* history,
                        InputStats* stats);

}  // namespace cb
