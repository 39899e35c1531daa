#include "app/brush/slice_sampler.h"

#include <algorithm>
#include <cmath>

namespace cb {

CuttingPlane cuttingPlane(const InkVolume& ink, float pressure, float tilt_x_deg, float tilt_y_deg,
                          float max_tilt_deg) {
  float tx = glm::radians(std::clamp(tilt_x_deg, -max_tilt_deg, max_tilt_deg));
  float ty = glm::radians(std::clamp(tilt_y_deg, -max_tilt_deg, max_tilt_deg));
  CuttingPlane plane;
  plane.point = glm::vec3(0.0f, ink.planeHeight(pressure), 0.0f);
  plane.normal = glm::normalize(glm::vec3(std::tan(tx), 1.0f, std::tan(ty)));
  // World x projected into the plane, then v completes a right-handed frame (v ≈ +z).
  glm::vec3 x(1.0f, 0.0f, 0.0f);
  plane.u = glm::normalize(x - glm::dot(x, plane.normal) * plane.normal);
  plane.v = glm::normalize(glm::cross(plane.u, plane.normal));
  return plane;
}

BrushSample marchSlab(const InkVolume& ink, const CuttingPlane& plane, const Brush3DParams& p) {
  const int n = p.sample_size;
  BrushSample out(n);
  // One-voxel steps across the slab (trilinear lookups in between).
  float voxel = 2.0f / float(ink.size());
  int steps = std::max(1, int(std::ceil(p.slab_thickness / voxel)));
  float ds = p.slab_thickness / float(steps);
  // Texels whose slab segment stays outside the ink's radius are empty: skip them.
  float reach = ink.inkRadius() + 0.5f * p.slab_thickness + voxel;
  // Single-threaded on purpose: the brush runs beside llvmpipe, which wants every core, and
  // on a loaded 2-core machine spawning workers made the slowest samples slower.
  for (int j = 0; j < n; ++j) {
    float b = ((j + 0.5f) / float(n)) * 2.0f - 1.0f;
    for (int i = 0; i < n; ++i) {
      float a = ((i + 0.5f) / float(n)) * 2.0f - 1.0f;
      glm::vec3 q = plane.point + a * plane.u + b * plane.v;
      if (q.x * q.x + q.z * q.z > reach * reach) continue;
      float optical = 0.0f;
      glm::vec3 step = ds * plane.normal;
      glm::vec3 x = q + (-0.5f * p.slab_thickness + 0.5f * ds) * plane.normal;
      for (int s = 0; s < steps; ++s, x += step) optical += ink.sample(x);
      out.at(i, j) = 1.0f - std::exp(-p.absorption * optical * ds);
    }
  }
  return out;
}

}  // namespace cb
