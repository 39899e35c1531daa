// The two erase styles of thesis §3.5 as free functions over the volume (OpenVDB tools style).
// Both return the voxel box they changed (already marked dirty) and change nothing outside it;
// bricks they leave all zero are released (Volume::releaseEmptyBrick).
#pragma once

#include <glm/glm.hpp>

#include "app/volume/volume.h"

namespace cb {

// Vacuum (§3.5.1): removes the cloud inside a sphere, with a smooth boundary: density is
// multiplied by smoothstep(r·(1 − soft), r, distance), so the hole's rim fades over the outer
// `soft` fraction of the radius instead of a hard cut. World units.
VoxelBox vacuumSphere(Volume& volume, glm::vec3 centre, float radius, float soft = 0.25f);

// Rub-out (§3.5.2): removes the cloud inside a cylinder of `radius` along the ray
// origin + t·dir (t ≥ 0, dir unit length), limited to the height range [y_min, y_max] (the 3D
// canvas). The rim fades over one voxel. World units.
VoxelBox rubOutCylinder(Volume& volume, glm::vec3 origin, glm::vec3 dir, float radius, float y_min,
                        float y_max);

}  // namespace cb
