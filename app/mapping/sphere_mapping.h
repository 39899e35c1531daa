// Sphere mapping (thesis §6.5): each circle's centre is cast from the paint camera onto the
// canvas altitude plane; the sphere there has the world radius the circle has at that depth.
// Voxels inside are filled and modulated by the pre-generated simplex-noise texture, so the
// sphere's surface is eroded irregularly and its interior density varies.
#pragma once

#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "app/mapping/circle_growth.h"
#include "app/mapping/mapping_config.h"
#include "app/mapping/paint_view_geometry.h"
#include "app/mapping/simplex_noise.h"
#include "app/scene/canvas.h"
#include "app/volume/volume.h"

namespace cb {

struct MappedSphere {
  glm::vec3 centre{0.0f};  // world
  float radius = 0.0f;     // world
  bool on_canvas = true;   // false: the centre's ray missed the canvas; the fallback plane was used
};

// Where the canvas is not hit (view parallel to it, ray above the horizon) the sphere is placed
// on the plane facing the camera through `fallback_point`.
std::vector<MappedSphere> mapCirclesToSpheres(const std::vector<Circle>& circles,
                                              const PaintViewGeometry& view, const Canvas& canvas,
                                              glm::vec3 fallback_point, float max_distance);

// Density of a point at normalised distance q = |p - centre| / radius from a sphere's centre,
// with noise texel n in [0, 1]: the surface sits at b = 1 − erosion·n, density fades to zero
// over `edge_softness` inside it and is scaled by (1 − m + m·n).
inline float sphereDensity(float q, float n, const SphereMappingConfig& c) {
  float b = 1.0f - c.noise_erosion * n;
  if (q >= b) return 0.0f;
  float fade = glm::min(1.0f, (b - q) / c.edge_softness);
  return c.density * fade * (1.0f - c.noise_modulation + c.noise_modulation * n);
}

// Radius the voxels of a sphere are filled to. The noise moves the surface inwards by
// erosion·n, n in [0, 1] (sphereDensity), so a sphere filled to the circle's own radius shows a
// silhouette smaller than the circle it came from: the paint view loses the stroke's rim
// (thesis §6.5 wants the mapped cloud to match the footprint; §6.6 only adds the pixels "that
// fall below the circle fill threshold"). Filled to r / (1 − erosion/2), the eroded surface
// lies on the circle's outline where the noise is at its middle, outside it where the noise is
// low and inside where it is high.
// Widened further so the paint view's ray through the circle's outline still crosses a chord
// of `outline_chord_voxels` (c): r' = √(r² + (c/2)²). Seen from the paint view the sphere is then
// opaque out to the circle instead of fading inside it; on a large sphere this changes nothing,
// on a stroke a few voxels thick it is what keeps the cloud as wide as the ink. A chord of 0
// (journals recorded before the key) is exactly the older r / (1 − erosion/2).
inline float sphereFillRadius(float circle_radius, float voxel_size, const SphereMappingConfig& c) {
  const float half_chord = 0.5f * c.outline_chord_voxels * voxel_size;
  if (half_chord == 0.0f) return circle_radius / (1.0f - 0.5f * c.noise_erosion);
  return std::sqrt(circle_radius * circle_radius + half_chord * half_chord) /
         (1.0f - 0.5f * c.noise_erosion);
}

// Max-merges the spheres into the volume (parallel over z slabs; each voxel is written by one
// chunk, so the result does not depend on the thread count). Returns the voxels touched; does
// not call markDirty.
VoxelBox fillSpheres(const std::vector<MappedSphere>& spheres, const NoiseTexture& noise,
                     const SphereMappingConfig& config, Volume& volume);

// Voxel box of a world-space sphere, clipped to the volume.
VoxelBox sphereVoxelBox(const MappedSphere& sphere, const Volume& volume);

}  // namespace cb
