// Pens with only a tip (no pressure axis: eGalax, Nexio and IRTOUCH touch screens' pens, some
// Wacom-protocol styli of kiosks): their samples carry pressure 0 while the tip is down, which
// would paint nothing. The painter gives them a pressure level of its own (−/+ keys), written
// into `pressure` while the tip is down; `pressure_raw` stays 0, the device's truth, and the
// journal records both, so a replay paints the same.
#pragma once

#include <algorithm>

#include "drivers/core/pen_sample.h"

namespace cb {

inline bool penHasPressure(const PenDeviceInfo& d) {
  return d.pressure_max > 0;
}

// Sets `s.pressure` to `level` (clamped to 0.05..1) while the tip is down, for a device without
// pressure; returns whether it did. Samples of pens with pressure, and samples that carry a
// pressure anyway (a journal without its device record), are left alone.
inline bool applyTipOnlyPressure(PenSample& s, const PenDeviceInfo& d, float level) {
  if (penHasPressure(d) || s.pressure > 0.0f || s.pressure_raw != 0 || !s.in_proximity ||
      !(s.buttons & kPenTip))
    return false;
  s.pressure = std::clamp(level, 0.05f, 1.0f);
  return true;
}

}  // namespace cb
