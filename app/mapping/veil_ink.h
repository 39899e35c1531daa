// Ink in the veil is left out. The painter veils the screen where a stroke cannot land: where a
// pixel's ray does not meet the canvas's mid-plane inside the sky as wide as it may grow, ahead
// of the near plane (app/scene/drawable_region.h; thesis §6.5 casts sphere centres onto that
// plane). Before a finished stroke is mapped, its footprint pixels there are cleared, so the
// mapping places only ink that lands, and only that ink can grow the sky (stroke_reach.h).
// Otherwise veiled ink would go to the mapping's fallback plane through the sky's centre, and its
// reach, unknown, would grow the sky to its widest. A pure function of the stroke and the sky's
// widest extent (both journalled), so a replay leaves out the same ink.
#pragma once

#include <glm/glm.hpp>

#include "app/brush/stroke_result.h"

namespace cb {

// Clears `stroke`'s footprint pixels above `empty_threshold` whose rays, in the stroke's own view
// and canvas, cannot land inside the world x/z box [sky_min, sky_max]; returns how many it
// cleared (0: the stroke is untouched).
long long leaveOutVeiledInk(StrokeResult* stroke, glm::vec3 sky_min, glm::vec3 sky_max,
                            float empty_threshold);

}  // namespace cb
