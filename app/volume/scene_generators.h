// Seeded scene generators: the bundled cumulus, the sparse "puffs" scene of the benchmarks and a
// few exact test shapes. Every generator is a pure function of its arguments (same dims and seed
// ⇒ byte-identical volume on any thread count), written with cb::parallelFor over z slices.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "app/volume/volume.h"

namespace cb {

// A cumulus: a flat-bottomed heap of overlapping spherical blobs (a large base, a domed tower and
// side turrets placed by `seed`), with density 1 deep inside, falling to 0 over a soft rim that is
// broken up by three octaves of value noise. Fills roughly 30% of the voxels with density > 0.
// World box [-1,1]^3, y up; the base sits at y ≈ -0.42.
Volume makeBundledCumulus(glm::ivec3 dims = glm::ivec3(256), uint32_t seed = 1);

// About 20 small soft puffs (radius 0.05–0.11 in world units) scattered through the box by
// `seed`; fewer than 3% of the voxels are non-zero. The benchmark scene for empty-space skipping.
Volume makeSparsePuffs(glm::ivec3 dims = glm::ivec3(256), uint32_t seed = 2);

// An empty volume with one voxel set to `density` (tests: every planted voxel must show).
Volume makeSingleVoxel(glm::ivec3 dims, glm::ivec3 voxel, float density = 1.0f);

// A sphere of world-space `radius` around `centre`: density `density` inside radius·(1−soft),
// falling linearly to 0 at the radius.
Volume makeSphere(glm::ivec3 dims, glm::vec3 centre, float radius, float density = 1.0f,
                  float soft = 0.2f);

// A soft ball of `radius` voxels around `centre` (voxel coordinates) merged by max into `v`,
// density min(1, 1.5·(1 − r/radius)), its box marked dirty: a stroke-sized test and benchmark
// shape.
void mergeSoftBall(Volume* v, glm::vec3 centre, float radius);

// Fraction of voxels with density > 0 (a scene statistic used by tests and benchmarks).
double filledFraction(const Volume& volume);

}  // namespace cb
