// The 3D brush's 2D sample (thesis §5.3.1, Fig. 5.7): pen tilt sets the normal of a cutting
// plane through the ink volume and pressure its height; a thin slab around the plane is
// ray-marched along the normal ("plain volumetric rendering ... through a thin slab ... usually
// 10 times smaller than the 64³ ink dataset") into a square image splatted at the pen tip.
#pragma once

#include <glm/glm.hpp>

#include "app/brush/brush_config.h"
#include "app/brush/brush_sample.h"
#include "app/brush/ink_volume.h"

namespace cb {

struct CuttingPlane {
  glm::vec3 point{0.0f};  // on the plane, above the volume's centre
  glm::vec3 normal{0.0f, 1.0f, 0.0f};
  glm::vec3 u{1.0f, 0.0f, 0.0f};  // in-plane axis shown along footprint +x
  glm::vec3 v{0.0f, 0.0f, 1.0f};  // in-plane axis shown along footprint +y (down)
};

// Normal n ∝ (tan θx, 1, tan θy) with each tilt clamped to ±max_tilt_deg: a pen leaning towards
// +x lowers the plane on the +x side, so the rounded sphere body lies under the lean and the
// plume's noise ("split tip") on the opposite side, where a real brush's tip trails.
CuttingPlane cuttingPlane(const InkVolume& ink, float pressure, float tilt_x_deg, float tilt_y_deg,
                          float max_tilt_deg);

// Ray-marches the slab |(q − point)·n| ≤ slab/2 for every sample texel: value = 1 − exp(−k ∫ρ).
BrushSample marchSlab(const InkVolume& ink, const CuttingPlane& plane, const Brush3DParams& params);

}  // namespace cb
