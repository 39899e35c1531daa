// The 3D canvas (thesis §3.4): a horizontal slab of the sky volume at an altitude, with a
// thickness. Strokes are painted from the current camera (the paint view) and mapped into it.
#pragma once

#include <glm/glm.hpp>

namespace cb {

struct Canvas {
  float altitude = 0.0f;   // world y of the slab's mid-plane
  float thickness = 0.6f;  // world units, the slab spans altitude ± thickness/2

  float bottom() const { return altitude - 0.5f * thickness; }
  float top() const { return altitude + 0.5f * thickness; }
  // Intersects a ray with the canvas mid-plane; false when (nearly) parallel or behind.
  bool intersectMidPlane(glm::vec3 origin, glm::vec3 dir, float* t) const {
    if (glm::abs(dir.y) < 1e-6f) return false;
    float s = (altitude - origin.y) / dir.y;
    if (s <= 0.0f) return false;
    *t = s;
    return true;
  }
};

}  // namespace cb
