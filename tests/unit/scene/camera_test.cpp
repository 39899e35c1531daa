#include "app/scene/camera.h"

#include <gtest/gtest.h>

namespace cb {
namespace {

TEST(Camera, CentrePixelRayPointsAtTarget) {
  Camera c = Camera::reference();
  glm::vec3 o, d;
  c.pixelRay(159.5f, 99.5f, 320, 200, &o, &d);  // pixel centre at the image centre
  glm::vec3 want = glm::normalize(c.target - c.eye);
  EXPECT_GT(glm::dot(d, want), 0.99999f);
  EXPECT_NEAR(glm::length(o - c.eye), c.near_plane, 1e-3);
}

TEST(Camera, TopRowLooksUpwardsOfCentre) {
  Camera c = Camera::reference();
  glm::vec3 o, top, mid;
  c.pixelRay(160, 0, 320, 200, &o, &top);
  c.pixelRay(160, 100, 320, 200, &o, &mid);
  EXPECT_GT(top.y, mid.y);
  // Half the vertical field of view between the centre and the top edge.
  float angle = glm::degrees(std::acos(glm::dot(top, glm::normalize(c.target - c.eye))));
  EXPECT_NEAR(angle, 22.5f, 0.3f);
}

TEST(Camera, OrbitKeepsDistanceAndHeight) {
  Camera c = Camera::reference();
  Camera o = c.orbited(90.0f);
  EXPECT_NEAR(glm::length(o.eye - o.target), glm::length(c.eye - c.target), 1e-5);
  EXPECT_NEAR(o.eye.y, c.eye.y, 1e-5);
  EXPECT_GT(glm::length(o.eye - c.eye), 1.0f);
}

}  // namespace
}  // namespace cb
