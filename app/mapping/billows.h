// Billows (thesis §6.3–6.5: a stroke's cloud is spheres of many sizes grown inside the
// footprint, not a tube): circle growth fills a stroke of even width with circles of one size,
// and their spheres made a constant-radius tube. Each sphere's radius is scaled by
// 1 + A·u², u a smooth seeded simplex noise in [0, 1] of its circle's centre (footprint pixels)
// with features F × the stroke's median circle radius across, so neighbouring spheres swell
// together into lobes a few circles long (never below the circle: the footprint stays covered): the
// silhouette's half-width varies along the stroke and the lobes rise above and below the canvas. A
// = spheres.billow_amplitude, F = spheres.billow_feature_radii; seeded by the stroke index, so a
// replay is identical.
#pragma once

#include <cstdint>
#include <vector>

#include "app/mapping/circle_growth.h"
#include "app/mapping/mapping_config.h"
#include "app/mapping/sphere_mapping.h"

namespace cb {

// Scales spheres[i].radius (the sphere of circles[i]); A = 0 leaves them untouched.
void billowSpheres(const std::vector<Circle>& circles, uint32_t stroke_index,
                   const SphereMappingConfig& config, std::vector<MappedSphere>* spheres);

// Edge puffs (thesis §6.6's edge details, Fig. 6.16, made round): with probability
// P = spheres.puff_probability a sphere carries a small sphere on its surface (a stroke of
// fewer than 8 spheres gets 8 such chances in all, shared among them), out sideways or
// up (azimuth uniform, elevation 0–40°), its centre on the surface, radius 0.35–0.6 R: the bumps of
// a cumulus outline on a dot as on a long stroke. Seeded by (stroke index, sphere); P = 0 none.
std::vector<MappedSphere> edgePuffs(const std::vector<MappedSphere>& spheres, uint32_t stroke_index,
                                    const SphereMappingConfig& config);

}  // namespace cb
