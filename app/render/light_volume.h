// The light volume of thesis §4.5 (Alg. 5): per voxel, the transmittance towards a directional
// sun, T = Π (1 − k·density) over unit steps from the voxel to the volume's edge along the light
// direction (the direction from the volume centre to the light ball). The shading stage turns it
// into the thesis's strength S(I) with I = 1 − T (see shaders/shade_thesis.glsl).
//
// Two ways to compute it, both free functions over the grid:
//  - sweepLightVolume: slice by slice along the light's major axis, starting at the light side.
//    Each voxel takes the (bilinearly interpolated) transmittance of the point one slice
//    upstream and attenuates it by its own voxel over that step: T(x) = (1 − k·d(x))^ℓ · T(x+u),
//    u = L / |L_major| (one slice towards the light), ℓ = |u| in voxels. O(voxels), parallel
//    within each slice. Alg. 5 starts its unit steps at the voxel itself, which weights the
//    voxel's own density by ½ more than the integral from its centre; to match, the stored T
//    weights the own voxel by (ℓ+1)/2 while the value passed downstream ("through") carries ℓ.
//  - marchLightReference: the straightforward per-voxel march of Alg. 5 (trilinear density at
//    x + i·L̂, i = 0, 1, …, until the point leaves the box). O(voxels × edge length); used by
//    tests and the benchmark as the reference.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "app/scene/light.h"
#include "app/volume/box.h"
#include "app/volume/volume.h"

namespace cb {

struct LightVolume {
  glm::ivec3 dims{0};
  glm::vec3 direction{0.0f};         // unit, voxel space, towards the light
  float extinction = -1.0f;          // k the volume was computed with
  std::vector<float> transmittance;  // T per voxel, x fastest; 1 = fully lit
  // The sweep's running product including each voxel's whole step (see sweepLightVolume).
  std::vector<float> through;

  bool matches(const Volume& volume, const Light& light) const;
  float at(int x, int y, int z) const {
    return transmittance[(size_t(z) * dims.y + size_t(y)) * dims.x + size_t(x)];
  }
};

// The light direction in voxel space (unit) for `light` shining on `volume`.
glm::vec3 lightDirectionInVoxels(const Volume& volume, const Light& light);

// Brings `light_volume` up to date. If it was computed for another light, extinction or dims,
// recomputes everything; otherwise recomputes the voxels a density change in `dirty` reaches:
// the dirty box, then slice by slice away from the light the voxels whose upstream footprint saw
// a change above 1e-6 (so the update stops where the edit's shadow fades or meets shadow that
// is already black). Returns the bounding box of the voxels rewritten (empty if none).
VoxelBox sweepLightVolume(LightVolume& light_volume, const Volume& volume, const Light& light,
                          const VoxelBox& dirty);

// The per-voxel reference march of Alg. 5 (slow: for tests and benchmarks). With z_step > 1 only
// the z slices z % z_step == 0 are computed (the others are set to -1), for timing and checking
// a sample of a large volume.
std::vector<float> marchLightReference(const Volume& volume, const Light& light, int z_step = 1);

// The thesis's shading strength S = 0.55 + cos(0.4 − I·π)/2.2 with I = 1 − T (§4.5.2, Fig. 4.19);
// the same formula as shaders/shade_thesis.glsl, for CPU checks.
float thesisStrength(float transmittance);

}  // namespace cb
