// From calibration/ to the brushes: a MappedSample (filtered screen position, calibrated
// pressure, contact with hysteresis, tilt) becomes a BrushInput in footprint pixels. The
// footprint uses the unpredicted position; the prediction is for the cursor only.
#pragma once

#include "app/brush/brush_input.h"
#include "calibration/mapped_sample.h"

namespace cb {

// `footprint_scale`: footprint pixels per screen pixel (config stroke.footprint_scale).
BrushInput brushInputFromCalibrated(const MappedSample& sample, float footprint_scale);
// The same with a scale per axis (a brush size's coarser footprint, stroke_engine.h).
BrushInput brushInputFromCalibrated(const MappedSample& sample, glm::vec2 footprint_scale);

}  // namespace cb
