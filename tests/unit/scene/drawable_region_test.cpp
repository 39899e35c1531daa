#include "app/scene/drawable_region.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "app/scene/paint_camera.h"

namespace cb {
namespace {

const glm::vec3 kMin(-1.0f), kMax(1.0f);

// The definition, through the camera's own pixel rays: the ray meets the canvas mid-plane
// inside the box's x/z extent.
bool landsByDefinition(const Camera& c, const Canvas& canvas, int x, int y, int w, int h) {
  glm::vec3 o, d;
  c.pixelRay(float(x), float(y), w, h, &o, &d);
  float t;
  if (!canvas.intersectMidPlane(o, d, &t)) return false;
  const glm::vec3 p = o + d * t;
  return p.x >= kMin.x && p.x <= kMax.x && p.z >= kMin.z && p.z <= kMax.z;
}

TEST(DrawableRegion, PixelTestRowSpansAndPixelRaysAgree) {
  const int w = 320, h = 180;
  for (const Camera& c : {Camera::reference(), Camera::reference().orbited(30.0f),
                          defaultPaintCamera(Canvas{}, kMin, kMax, float(w) / float(h))}) {
    const DrawableRegion region(c, Canvas{}, kMin, kMax, w, h);
    const std::vector<uint8_t> mask = region.mask();
    long long landable = 0, disagree_span = 0, disagree_rays = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const bool by_pixel = region.canLandPixel(x, y);
        landable += by_pixel;
        disagree_span += by_pixel != (mask[size_t(y) * w + x] != 0);
        disagree_rays += by_pixel != landsByDefinition(c, Canvas{}, x, y, w, h);
      }
    ASSERT_GT(landable, 1000);
    EXPECT_NEAR(double(landable), double(region.landablePixels()), 2.0);
    // Only pixels whose centre lies on the outline (float rounding) may differ.
    EXPECT_LE(disagree_span, 2);
    EXPECT_LE(disagree_rays, 2);
  }
}

TEST(DrawableRegion, NothingLandsWhenTheCanvasIsOutsideTheBoxOrBehindTheCamera) {
  Canvas high;
  high.altitude = 1.5f;
  EXPECT_EQ(DrawableRegion(Camera::reference(), high, kMin, kMax, 64, 36).landablePixels(), 0);
  Camera up = Camera::reference();
  up.eye = glm::vec3(0.0f, -3.0f, 3.0f);
  up.target = glm::vec3(0.0f, -4.0f, 0.0f);  // below the canvas, looking down, away from it
  EXPECT_EQ(DrawableRegion(up, Canvas{}, kMin, kMax, 64, 36).landablePixels(), 0);
}

TEST(DrawableRegion, OutlineHugsTheLandablePixels) {
  const Camera c = Camera::reference();
  const DrawableRegion region(c, Canvas{}, kMin, kMax, 640, 360);
  ASSERT_EQ(region.outline().size(), 4u);  // the whole rectangle is in front of the camera
  glm::vec2 lo(1e9f), hi(-1e9f);
  for (glm::vec2 p : region.outline()) lo = glm::min(lo, p), hi = glm::max(hi, p);
  int x0 = 640, x1 = -1, y0 = 360, y1 = -1;
  for (int y = 0; y < 360; ++y)
    for (int x = 0; x < 640; ++x)
      if (region.canLandPixel(x, y))
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  EXPECT_NEAR(float(x0), lo.x, 1.0f);
  EXPECT_NEAR(float(x1 + 1), hi.x, 1.0f);
  EXPECT_NEAR(float(y0), lo.y, 1.0f);
  EXPECT_NEAR(float(y1 + 1), hi.y, 1.0f);
}

}  // namespace
}  // namespace cb
