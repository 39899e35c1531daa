// The paint view's camera (thesis §3.4: the user picks a view direction onto the 3D canvas;
// §7.7.5 problem 2: from a near-frontal view the visible part of the canvas is small, which
// "significantly increases the painting difficulty").
//
//   framePaintCamera     a camera at a given yaw and elevation that frames the drawable region
//                        (drawable_region.h) as tightly as the screen allows
//   defaultPaintCamera   the painter's starting view: framed, 3/4 from above, box-aligned
//   assessPaintView      elevation and fill fraction of a view, and whether it is good to paint
//   nearestGoodPaintView for a (nearly) edge-on view: same yaw and target, raised elevation
//
// Elevation is the angle of the view axis below the horizontal canvas plane (0 = edge-on,
// 90 = top-down). Yaw 0 puts the eye on the +z side looking towards −z; yaw grows as
// Camera::orbited turns the eye (counter-clockwise seen from above).
#pragma once

#include <glm/glm.hpp>

#include "app/scene/camera.h"
#include "app/scene/canvas.h"

namespace cb {

struct PaintFraming {
  float yaw_deg = 0.0f;
  float elevation_deg = 40.0f;
  float fov_y_deg = 35.0f;
  float margin = 0.02f;  // fraction of each half-screen left free around the region
  // The region's sides touch the screen's sides at this fraction of the canvas's depth range
  // (0 = its far edge, 1 = its near edge: every corner on screen). Nearer than that, the
  // canvas spills past the screen's sides; far and near edges always fit vertically.
  float side_fit_depth = 0.6f;
};

// The camera with the framing's yaw, elevation and field of view whose view of the canvas
// mid-plane rectangle inside the box (x/z extent at canvas.altitude) just fits the screen
// inset by the margin: touching two opposite sides (the eye halfway between the positions
// that would touch either of the other two). Its target
// is where the view axis meets the canvas mid-plane, so Camera::orbited turns about the
// middle of the painted region. Requires 0 < elevation < 90.
Camera framePaintCamera(const Canvas& canvas, glm::vec3 box_min, glm::vec3 box_max, float aspect,
                        const PaintFraming& framing = {});

// The painter's default paint view: framePaintCamera with PaintFraming's defaults. Seen along
// a box axis the region is a trapezoid (seen along the diagonal, as Camera::reference() does,
// it is a diamond that fills at most half of its bounding box). At 40° elevation, a 35° field
// of view and side_fit_depth 0.6 it fills ~89 % of a 16:9 screen, and ~96 % of the canvas is on
// screen (the near corners spill past the sides). With side_fit_depth 1 (all of the canvas on
// screen) the best 16:9 fill is ~76 %, at 50° elevation.
Camera defaultPaintCamera(const Canvas& canvas, glm::vec3 box_min, glm::vec3 box_max, float aspect);

// Angle of the view axis below the horizontal, in degrees (negative when looking up).
float viewElevationDeg(const Camera& camera);

struct GoodViewCriteria {
  float min_elevation_deg = 20.0f;  // below this the view grazes the canvas (edge-on)
  double min_fill_fraction = 0.25;  // ... or too little of the screen can take a stroke
  float max_elevation_deg = 80.0f;  // nearestGoodPaintView raises the view at most this far
  float elevation_step_deg = 0.5f;  // ... in steps of this
};

struct PaintViewAssessment {
  float elevation_deg = 0.0f;
  double fill_fraction = 0.0;  // DrawableRegion::fillFraction
  bool edge_on = false;        // elevation below criteria.min_elevation_deg
  bool good = false;           // not edge-on and fill >= criteria.min_fill_fraction
};

PaintViewAssessment assessPaintView(const Camera& camera, const Canvas& canvas, glm::vec3 box_min,
                                    glm::vec3 box_max, int width, int height,
                                    const GoodViewCriteria& criteria = {});

// The camera itself when its view is good; otherwise the same camera turned upwards about its
// target (same yaw, distance and field of view) to the lowest elevation at which the view is
// good. If no elevation up to max_elevation_deg is good, the one with the largest fill fraction
// among those that are not edge-on.
Camera nearestGoodPaintView(const Camera& camera, const Canvas& canvas, glm::vec3 box_min,
                            glm::vec3 box_max, int width, int height,
                            const GoodViewCriteria& criteria = {});

// The camera turned about its target to `elevation_deg`, keeping yaw, distance and the rest.
Camera withElevation(const Camera& camera, float elevation_deg);

}  // namespace cb
