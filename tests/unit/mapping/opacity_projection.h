// Test helpers. A CPU opacity integrator, used where a check needs the density along exact
// footprint pixel rays (silhouettes go through the real VolumeRenderer, see
// stroke_mapper_render_test.cpp). It marches each pixel ray of a
// camera through the volume one voxel per step, sampling the nearest voxel, with the
// transmittance convention of Light::extinction, T = Π (1 − k·density), k = 0.12 per step of
// one voxel of the default 256³ volume over [-1,1]³ (1/128 world units); steps of another
// length s count as (1 − k·density)^(s·128). So opacity does not depend on the grid resolution.
// Returns per-pixel accumulated opacity 1 − T, row 0 at the top.
#pragma once

#include <vector>

#include "app/scene/camera.h"
#include "app/volume/volume.h"

namespace cb::test {

std::vector<float> projectOpacity(const Volume& volume, const Camera& camera, int width, int height,
                                  float extinction_per_reference_voxel = 0.12f);

// Structure-tensor anisotropy of an image along a unit image direction u (x right, y down):
// gradient energy across u over gradient energy along u. Streaks running along u give a large
// value; isotropic texture gives about 1.
double anisotropyAlong(const std::vector<float>& image, int width, int height, glm::vec2 u);

}  // namespace cb::test
