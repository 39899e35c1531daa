// Circle growth (thesis §6.3–6.4): fills the body of a footprint with overlapping circles.
//
// The first circle grows at the middle white pixel along the stroke path; each accepted circle
// proposes candidates on its perimeter in 16 directions. A candidate of radius r counts, over
// the pixels within r of its centre (§6.3.3):
//   N_p  pixels in the circle (pixels outside the footprint count as empty),
//   N_w  white pixels of the footprint (value >= white_threshold),
//   N_e  empty pixels (value <= empty_threshold, or already covered by an accepted circle),
// and is accepted at R_w = N_w/N_p >= 0.8; the direction is dropped at R_e = N_e/N_p > 0.5.
// Accepted circles are masked out (they count as empty for later candidates). White is judged
// on the footprint itself, so every accepted circle is >= 80% white in the unmasked footprint.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "app/brush/stroke_result.h"
#include "app/mapping/mapping_config.h"

namespace cb {

struct Circle {
  glm::vec2 centre{0.0f};  // footprint pixels (pixel (x, y) has its centre at (x, y))
  int radius = 0;          // footprint pixels
  int step = 0;            // growth step that accepted it (0 = a seed circle)
};

struct CircleCounts {
  long long pixels = 0, white = 0, empty = 0;  // N_p, N_w, N_e
  double whiteRatio() const { return pixels ? double(white) / double(pixels) : 0.0; }
  double emptyRatio() const { return pixels ? double(empty) / double(pixels) : 1.0; }
};

struct CircleGrowthResult {
  std::vector<Circle> circles;   // in acceptance order
  std::vector<uint8_t> covered;  // per footprint pixel: 1 inside an accepted circle
  int steps = 0;                 // growth steps (Algorithm 6's outer loop), all seeds together
  long long attempts = 0;        // circle tests (pixel analyses) performed
  int seeds = 0;                 // circles grown from a seed point rather than a parent
};

// How the radius of a candidate is chosen.
enum class RadiusSearch : uint8_t {
  kBinary = 0,       // §6.4.6: binary search between min_radius and the initial radius
  kLinearStep4 = 1,  // the thesis's starting point: radius decreasing 4 px per attempt
};

// The fast variant: per-row prefix counts make a circle test O(radius) instead of O(radius²),
// binary search on the radius. Deterministic and single-threaded by design (each acceptance
// changes the mask the next test reads; see README for the measurements behind this choice).
CircleGrowthResult growCircles(const Footprint& footprint, const std::vector<StrokePoint>& path,
                               const CircleGrowthConfig& config);

// The straightforward variant the thesis started from (Algorithm 6 + 7): every test traverses
// the circle's pixel block, radius decreasing 4 px per attempt. One thread. The benchmark
// baseline.
CircleGrowthResult growCirclesStraightforward(const Footprint& footprint,
                                              const std::vector<StrokePoint>& path,
                                              const CircleGrowthConfig& config);

// The thresholds growth actually uses for this footprint: with white_relative_to_peak the white
// threshold is scaled by the footprint's peak value (never below the empty threshold).
CircleGrowthConfig effectiveCircleConfig(const Footprint& footprint,
                                         const CircleGrowthConfig& config);

// Counts a circle pixel by pixel with config's thresholds as given. `covered` may be null (the
// unmasked footprint).
CircleCounts countCircle(const Footprint& footprint, const std::vector<uint8_t>* covered,
                         glm::vec2 centre, int radius, const CircleGrowthConfig& config);

// Pixels of row y inside the circle: [*x0, *x1] (may lie outside the footprint); false if the
// row misses it. A pixel is inside when (x-cx)² + (y-cy)² <= r², evaluated in double.
bool circleRowSpan(glm::vec2 centre, int radius, int y, int* x0, int* x1);

}  // namespace cb
