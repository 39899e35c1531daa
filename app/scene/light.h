// The sun (thesis §4.5): a directional light. The direction (a unit vector pointing towards the
// sun) is what the light mode sets, journals and undoes; it does not depend on where the volume
// is, so growing or moving the sky changes no lighting. The light ball the user drags only sets
// this direction (seen from a fixed scene origin). config/render.toml's `[light] time_of_day`
// sets direction and colour from the sun of that hour (sun_position.h) instead; either way the
// renderer recomputes the light volume when the direction changes.
#pragma once

#include <glm/glm.hpp>

namespace cb {

struct Light {
  // Towards the sun; the default equals the earlier light ball at (3, 4, 1.5) seen from the
  // origin, the centre of the default sky box.
  glm::vec3 direction = glm::normalize(glm::vec3(3.0f, 4.0f, 1.5f));
  glm::vec3 colour{1.0f, 0.97f, 0.92f};
  float extinction = 0.12f;  // k in T = Π(1 − k·density), per voxel step

  // A sun in the direction of `p` from the origin (as the light ball and the older
  // `light.position` settings give it); `p` must not be the origin.
  static glm::vec3 directionTowards(glm::vec3 p) { return glm::normalize(p); }
};

}  // namespace cb
