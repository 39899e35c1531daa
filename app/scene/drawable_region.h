// Where a stroke can land (thesis §3.4, §6.5): a screen point of the paint view can become cloud
// when its ray meets the 3D canvas's mid-plane inside the volume's x/z extent, in front of the
// near plane. Sphere centres are cast onto that plane (§6.5); a ray that misses it lands on a
// fallback plane or outside the volume. The region is the image of a rectangle of the mid-plane,
// a convex polygon on screen, so every pixel row holds at most one run of landable pixels.
//
// Screen coordinates: x right, y down, pixel (x, y) covers [x, x+1) × [y, y+1) (the brushes'
// footprint convention), so its centre is (x + 0.5, y + 0.5), the point Camera::pixelRay uses.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "app/scene/camera.h"
#include "app/scene/canvas.h"

namespace cb {

class DrawableRegion {
 public:
  // box_min/box_max: the volume's world box. width × height: the paint view in pixels (the
  // footprint's size).
  DrawableRegion(const Camera& camera, const Canvas& canvas, glm::vec3 box_min, glm::vec3 box_max,
                 int width, int height);

  // True when the ray through the screen point meets the canvas mid-plane inside the box's x/z
  // extent, beyond the near plane. A dozen flops and one division: cheap enough per footprint
  // pixel while drawing.
  bool canLandAt(glm::vec2 screen_point) const;
  bool canLandPixel(int x, int y) const { return canLandAt({float(x) + 0.5f, float(y) + 0.5f}); }

  // Landable pixels of row y, [*x0, *x1] (pixel centres inside the region's outline); false
  // when none.
  bool rowSpan(int y, int* x0, int* x1) const;
  // One byte per pixel, row-major, row 0 at the top: 1 where a stroke can land.
  std::vector<uint8_t> mask() const;
  long long landablePixels() const;
  // Landable pixels over all pixels: how much of the screen a painter can paint on.
  double fillFraction() const;

  // The region's outline on screen (convex, in order; empty when no part of the mid-plane
  // rectangle lies in front of the camera or the canvas altitude is outside the box). It may
  // extend beyond the screen.
  const std::vector<glm::vec2>& outline() const { return outline_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_, height_;
  glm::vec3 eye_;
  // Ray direction of screen point (sx, sy) is dir0_ + sx·dir_x_ + sy·dir_y_, scaled so its
  // component along the view axis is 1 (its plane parameter is then the view depth).
  glm::vec3 dir0_, dir_x_, dir_y_;
  float altitude_, near_plane_;
  glm::vec2 lo_, hi_;  // the box's x/z extent
  bool altitude_inside_;
  std::vector<glm::vec2> outline_;
};

}  // namespace cb
