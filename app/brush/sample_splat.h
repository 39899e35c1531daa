// Splatting a brush sample onto the footprint (thesis §5.3.1: samples are "splatted into screen
// space repeatedly as the stylus pen moves" into a buffer that is never cleared during a stroke).
// Dabs combine by max, so the result does not depend on the order they land in.
#pragma once

#include <glm/glm.hpp>

#include "app/brush/brush_sample.h"
#include "app/brush/dispersion.h"
#include "app/brush/footprint_rect.h"
#include "app/brush/stroke_result.h"

namespace cb {

struct SplatParams {
  glm::vec2 centre_px{0.0f};  // footprint position of the sample's centre
  float diameter_px = 1.0f;   // the sample's full width on the footprint
  float gain = 1.0f;          // multiplies the sample's values
  float dispersion = 0.0f;    // 0..1, see dispersion.h
};

// Returns the footprint rectangle that was touched (clipped to the footprint).
FootprintRect splatSample(const BrushSample& sample, const SplatParams& params,
                          const DispersionField& field, Footprint* footprint);

// A soft round dot of radius `radius_px` (value `value` inside, 1 px linear edge), as used for
// bristle points of the skeleton brush.
FootprintRect splatDot(glm::vec2 centre_px, float radius_px, float value, float dispersion,
                       const DispersionField& field, Footprint* footprint);

}  // namespace cb
