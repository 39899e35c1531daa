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
  // Half-voxel steps across the slab.
  float voxel = 2.0f / float(ink.size());
  int steps = std::max(1, int(std::ceil(p.slab_thickness / (0.5f * voxel))));
  float ds = p.slab_thickness / float(steps);
  for (int j = 0; j < n; ++j) {
    float b = ((j + 0.5f) / float(n)) * 2.0f - 1.0f;
    for (int i = 0; i < n; ++i) {
      float a = ((i + 0.5f) / float(n)) * 2.0f - 1.0f;
      glm::vec3 q = plane.point + a * plane.u + b * plane.v;
      float optical = 0.0f;
      for (int s = 0; s < steps; ++s) {
        float offset = -0.5f * p.slab_thickness + (s + 0.5f) * ds;
        optical += ink.sample(q + offset * plane.normal) * ds;
      }
      out.at(i, j) = 1.0f - std::exp(-p.absorption * optical);
    }
  }
  return out;
}

}  // namespace cb
