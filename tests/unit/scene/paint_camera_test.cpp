#include "app/scene/paint_camera.h"

#include <cmath>

#include <gtest/gtest.h>

#include "app/scene/drawable_region.h"

namespace cb {
namespace {

const glm::vec3 kMin(-1.0f), kMax(1.0f);

// Screen position (x right, y down, in units of the half-screen: -1..1) of a world point.
glm::vec2 ndc(const Camera& c, float aspect, glm::vec3 p) {
  const glm::vec4 q = c.projection(aspect) * c.view() * glm::vec4(p, 1.0f);
  return glm::vec2(q) / q.w;
}

TEST(PaintCamera, DefaultViewFillsMostOfA16By9ScreenFromAThreeQuarterView) {
  for (glm::ivec2 size : {glm::ivec2(1280, 720), glm::ivec2(1920, 1080)}) {
    const Camera c = defaultPaintCamera(Canvas{}, kMin, kMax, float(size.x) / float(size.y));
    const double fill = DrawableRegion(c, Canvas{}, kMin, kMax, size.x, size.y).fillFraction();
    const double reference =
        DrawableRegion(Camera::reference(), Canvas{}, kMin, kMax, size.x, size.y).fillFraction();
    std::printf("%dx%d: default paint camera fills %.3f, Camera::reference() %.3f\n", size.x,
                size.y, fill, reference);
    EXPECT_GE(fill, 0.85);
    EXPECT_LT(reference, 0.2);
    // A 3D view: neither edge-on nor top-down, eye outside the box.
    EXPECT_GT(viewElevationDeg(c), 25.0f);
    EXPECT_LT(viewElevationDeg(c), 65.0f);
    EXPECT_GT(glm::max(glm::abs(c.eye.x), glm::max(c.eye.y, glm::abs(c.eye.z))), 1.0f);
  }
}

TEST(PaintCamera, FramingFitsTheWholeRegionTightlyWhenAskedTo) {
  const float aspect = 16.0f / 9.0f;
  for (float elevation : {30.0f, 45.0f, 60.0f}) {
    PaintFraming framing;
    framing.elevation_deg = elevation;
    framing.side_fit_depth = 1.0f;
    framing.yaw_deg = 20.0f;
    const Camera c = framePaintCamera(Canvas{}, kMin, kMax, aspect, framing);
    EXPECT_NEAR(viewElevationDeg(c), elevation, 1e-3f);
    glm::vec2 lo(1e9f), hi(-1e9f);
    for (int i = 0; i < 4; ++i) {
      const glm::vec2 p =
          ndc(c, aspect, glm::vec3(i & 1 ? 1.0f : -1.0f, 0.0f, i & 2 ? 1.0f : -1.0f));
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    const float inset = 1.0f - framing.margin;
    EXPECT_GE(lo.x, -inset - 1e-4f);
    EXPECT_LE(hi.x, inset + 1e-4f);
    EXPECT_GE(lo.y, -inset - 1e-4f);
    EXPECT_LE(hi.y, inset + 1e-4f);
    // Tight: two opposite sides touched.
    const bool horizontal = std::abs(hi.x - inset) < 1e-3f && std::abs(lo.x + inset) < 1e-3f;
    const bool vertical = std::abs(hi.y - inset) < 1e-3f && std::abs(lo.y + inset) < 1e-3f;
    EXPECT_TRUE(horizontal || vertical) << elevation;
    // The target is on the canvas mid-plane, on the view axis.
    EXPECT_NEAR(c.target.y, 0.0f, 1e-4f);
  }
}

TEST(PaintCamera, NearestGoodViewRaisesAnEdgeOnViewJustEnough) {
  const int w = 640, h = 360;
  const Camera edge_on = withElevation(framePaintCamera(Canvas{}, kMin, kMax, 16.0f / 9.0f), 4.0f);
  const GoodViewCriteria criteria;
  const PaintViewAssessment before = assessPaintView(edge_on, Canvas{}, kMin, kMax, w, h);
  EXPECT_TRUE(before.edge_on);
  EXPECT_FALSE(before.good);

  const Camera good = nearestGoodPaintView(edge_on, Canvas{}, kMin, kMax, w, h, criteria);
  const PaintViewAssessment after = assessPaintView(good, Canvas{}, kMin, kMax, w, h, criteria);
  EXPECT_TRUE(after.good);
  EXPECT_GT(after.fill_fraction, before.fill_fraction);
  // Same yaw, target, distance and lens; only the elevation changed.
  const glm::vec3 a = edge_on.eye - edge_on.target, b = good.eye - good.target;
  EXPECT_NEAR(std::atan2(a.x, a.z), std::atan2(b.x, b.z), 1e-4f);
  EXPECT_NEAR(glm::length(a), glm::length(b), 1e-4f);
  EXPECT_EQ(good.target, edge_on.target);
  EXPECT_EQ(good.fov_y_deg, edge_on.fov_y_deg);
  // Nearest: one step lower is not good.
  const Camera lower = withElevation(good, viewElevationDeg(good) - criteria.elevation_step_deg);
  EXPECT_FALSE(assessPaintView(lower, Canvas{}, kMin, kMax, w, h, criteria).good);

  // A good view is kept as it is.
  const Camera fine = defaultPaintCamera(Canvas{}, kMin, kMax, 16.0f / 9.0f);
  const Camera kept = nearestGoodPaintView(fine, Canvas{}, kMin, kMax, w, h, criteria);
  EXPECT_EQ(kept.eye, fine.eye);
}

TEST(PaintCamera, WithElevationKeepsYawAndOrbitAddsToIt) {
  const Camera c = Camera::reference();
  const Camera raised = withElevation(c, 60.0f);
  EXPECT_NEAR(viewElevationDeg(raised), 60.0f, 1e-3f);
  const Camera turned = withElevation(c.orbited(40.0f), 60.0f);
  EXPECT_NEAR(glm::length(turned.eye - raised.orbited(40.0f).eye), 0.0f, 1e-4f);
}

}  // namespace
}  // namespace cb
