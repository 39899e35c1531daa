// Raw device units -> physical units for a PenSample, shared by every backend so that the same
// raw values always become the same millimetres, degrees and normalised pressure.
#pragma once

#include "drivers/core/pen_sample.h"

namespace cb {

inline float clampUnit(float v) {
  return v < 0.0f ? 0.0f : (v > 1.0f ? 1.0f : v);
}

// Fills x_mm, y_mm, pressure, tilt_x_deg, tilt_y_deg and distance from the raw fields.
// Resolutions of 0 leave the raw value (positions stay 0 mm; tilts are taken as degrees).
// Normalised pressure and distance are clamped to 0..1 (a device may report past its maximum).
inline void convertPenUnits(PenSample& s, const PenDeviceInfo& d) {
  s.x_mm = d.x_res > 0 ? s.x_raw / d.x_res : 0.0;
  s.y_mm = d.y_res > 0 ? s.y_raw / d.y_res : 0.0;
  s.pressure =
      d.pressure_max > 0 ? clampUnit(static_cast<float>(s.pressure_raw) / d.pressure_max) : 0.0f;
  s.tilt_x_deg = static_cast<float>(d.tilt_res > 0 ? s.tilt_x_raw / d.tilt_res : s.tilt_x_raw);
  s.tilt_y_deg = static_cast<float>(d.tilt_res > 0 ? s.tilt_y_raw / d.tilt_res : s.tilt_y_raw);
  s.distance =
      d.distance_max > 0 ? clampUnit(static_cast<float>(s.distance_raw) / d.distance_max) : 0.0f;
}

// The sample that ends a stroke when the pen leaves proximity (or the device goes away): the
// last position, tool and tilt, with no contact, no buttons and no pressure.
inline PenSample proximityOutSample(const PenSample& last, int64_t t_ns) {
  PenSample s = last;
  s.t_ns = t_ns;
  s.in_proximity = false;
  s.buttons = 0;
  s.pressure_raw = 0;
  s.pressure = 0.0f;
  return s;
}

// Field-by-field equality, timestamps aside (for tests comparing backends).
inline bool samePenState(const PenSample& a, const PenSample& b) {
  return a.x_raw == b.x_raw && a.y_raw == b.y_raw && a.x_mm == b.x_mm && a.y_mm == b.y_mm &&
         a.pressure_raw == b.pressure_raw && a.pressure == b.pressure &&
         a.tilt_x_raw == b.tilt_x_raw && a.tilt_y_raw == b.tilt_y_raw &&
         a.tilt_x_deg == b.tilt_x_deg && a.tilt_y_deg == b.tilt_y_deg &&
         a.distance_raw == b.distance_raw && a.distance == b.distance && a.buttons == b.buttons &&
         a.tool == b.tool && a.tool_id == b.tool_id && a.tool_serial == b.tool_serial &&
         a.in_proximity == b.in_proximity;
}

}  // namespace cb
