// The sun (thesis §4.5): a directional light whose direction points from the volume centre to
// the light ball the user moves, with a colour.
#pragma once

#include <glm/glm.hpp>

namespace cb {

struct Light {
  glm::vec3 position{3.0f, 4.0f, 1.5f};  // world position of the light ball
  glm::vec3 colour{1.0f, 0.97f, 0.92f};
  float extinction = 0.12f;  // k in T = Π(1 − k·density), per voxel step

  // Unit vector from the volume centre towards the light.
  glm::vec3 directionFrom(glm::vec3 centre) const { return glm::normalize(position - centre); }
};

}  // namespace cb
