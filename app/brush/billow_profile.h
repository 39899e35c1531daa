// The brush's edge along a stroke (thesis §6.3's "circles of many sizes", seed 001 §3's uneven
// wash edges): a texture brush's dab diameter is scaled by 1 + A·v in a lobe (v > 0) and
// 1 + A·v/3 in a neck (v < 0), v a smooth seeded noise in [-1, 1] of the stroke's arc length
// whose lattice points, L px apart, alternate between lobes and necks of seeded strength. A
// stroke of even pressure swells and narrows like a cloud's outline instead of being a tube of
// one width. The ink drawn is what the mapping grows circles and spheres in, so the cloud keeps
// the ink's shape (what you paint is what you get) and its billows. Seeded by the stroke index,
// so a replay paints the same edge.
#pragma once

#include <cstdint>

namespace cb {

// The factor for the dab at `arc_px` along stroke `stroke_index`: in [1 − A/3, 1 + A], its
// mean between 1 and 1 + A/4; exactly 1 when A = 0. `feature_px` > 0 is the distance between the
// noise's lattice points.
float billowFactor(uint32_t stroke_index, float arc_px, float feature_px, float amplitude);

}  // namespace cb
