// Reference strokes for tests and `cloudbrush bench mapping`: committed generators (path,
// pressure, tilt, seed), not images. A soft round brush is splatted along a smooth path at a
// fixed spacing; its radius follows the pressure, tilt widens one side, and a seeded bristle
// pattern thins the outer part of the stroke into streaks along the path (a dry-brush edge).
// These stand in for the brushes (app/brush) in mapping tests; the mapping itself only sees
// the resulting StrokeResult.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "app/brush/stroke_result.h"

namespace cb {

struct ReferenceBrush {
  float max_radius_px = 80.0f;  // radius at pressure 1
  float soft_edge_px = 3.0f;    // ramp from 1 to 0 at the rim
  float bristle_zone = 0.35f;   // outer fraction of the radius where bristles thin the ink
  float spacing_px = 2.0f;      // splat spacing along the path
};

// A stroke: control points in footprint pixels (a Catmull-Rom spline passes through them) with
// a pressure and a tilt (degrees, positive towards the path's left) at each.
struct ReferencePath {
  std::vector<glm::vec2> points;
  std::vector<float> pressure;
  std::vector<float> tilt_deg;
};

// Splats one path into a footprint (max-merged) and appends the consumed points to `path`.
void splatReferencePath(const ReferencePath& path, const ReferenceBrush& brush, uint32_t seed,
                        Footprint* footprint, std::vector<StrokePoint>* consumed);

// The paint view of the reference strokes: Camera::reference() moved closer (0.58 of its
// distance) so a stroke across most of the screen lands on the canvas inside the unit sky box.
Camera referencePaintCamera();

// The single thick stroke of thesis Fig. 6.6 (a curved stroke, thick in the middle, tapering),
// sized relative to width × height (the thesis used 1280×768).
StrokeResult makeThickStroke(int width, int height, uint32_t seed);
// The heart of thesis Fig. 6.9: a large filled shape laid down by crossing stroke flows.
StrokeResult makeHeart(int width, int height, uint32_t seed);

}  // namespace cb
