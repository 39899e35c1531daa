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

// A pan moves the view, not its direction: the point under the pen follows the pen. Projected,
// the old target moves left by exactly the panned pixels when the view pans right.
TEST(Camera, PanMovesThePointUnderThePenByTheDrag) {
  const Camera c = Camera::reference();
  const int w = 320, h = 200;
  const float pixels = 40.0f;
  const Camera p = c.panned(pixels * c.worldPerPixelAtTarget(h), 0.0f);
  EXPECT_NEAR(glm::length(p.eye - p.target), glm::length(c.eye - c.target), 1e-5);
  EXPECT_GT(glm::dot(glm::normalize(p.target - p.eye), glm::normalize(c.target - c.eye)), 0.99999f);
  const glm::vec4 clip = p.projection(float(w) / float(h)) * p.view() * glm::vec4(c.target, 1.0f);
  const float x = (clip.x / clip.w * 0.5f + 0.5f) * float(w);
  EXPECT_NEAR(x, 0.5f * float(w) - pixels, 0.05f);
  // Up moves the view up: the old target goes down the screen (y up in clip space).
  const Camera u = c.panned(0.0f, 10.0f * c.worldPerPixelAtTarget(h));
  const glm::vec4 up_clip = u.projection(float(w) / float(h)) * u.view() * glm::vec4(c.target, 1);
  EXPECT_LT(up_clip.y / up_clip.w, -0.05f);
}

TEST(Camera, ZoomScalesTheDistanceWithinLimits) {
  const Camera c = Camera::reference();
  const float d = glm::length(c.eye - c.target);
  EXPECT_NEAR(glm::length(c.zoomed(0.5f).eye - c.target), 0.5f * d, 1e-5);
  EXPECT_EQ(c.zoomed(0.5f).target, c.target);
  EXPECT_NEAR(glm::length(c.zoomed(1e-6f).eye - c.target), 0.05f, 1e-5);
  EXPECT_NEAR(glm::length(c.zoomed(1e6f).eye - c.target), 50.0f, 1e-3);
}

}  // namespace
}  // namespace cb
