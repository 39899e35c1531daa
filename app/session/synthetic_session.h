// Synthetic painting sessions: the committed synthetic brush strokes (app/brush/
// synthetic_strokes.h) as raw pen samples of a made-up tablet whose active area has the screen's
// aspect, so that the default calibration maps the whole tablet onto the whole screen. For the
// replay tests, the interactive test without hardware and demos.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "app/brush/synthetic_strokes.h"
#include "drivers/core/pen_sample.h"

namespace cb {

// A 0.005 mm/unit tablet as wide as 0.2 mm per screen pixel, 8192 pressure levels, tilt in
// degrees.
PenDeviceInfo syntheticTablet(int screen_width, int screen_height);

// Raw samples of `stroke` (its control points read as screen pixels) at `rate_hz` starting at
// t0_ns: a few hovering samples, the stroke with the tip down, then the lift and proximity out.
std::vector<PenSample> syntheticPenSamples(const SyntheticStroke& stroke,
                                           const PenDeviceInfo& tablet, int screen_width,
                                           int screen_height, double rate_hz, int64_t t0_ns);

// The reference strokes of the replay and paint tests, on a screen_width × screen_height screen.
std::vector<SyntheticStroke> referencePaintStrokes(int screen_width, int screen_height);

}  // namespace cb
