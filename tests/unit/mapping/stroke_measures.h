// Test helpers: what a painted stroke's cloud looks like, measured from the volume on the CPU.
//
// - `silhouetteOpacity`: the paint view's opacity as the renderer absorbs light (config/
//   render.toml extinction_per_voxel 0.35, nearest voxel) at 1/`downscale` of the screen, only
//   inside a pixel rectangle and only through a world box (the stroke's dirty box), so one stroke
//   costs tens of milliseconds.
// - `measureAlongPath`: along the drawn path (screen pixels), the silhouette's half-width
//   across the path (marching both ways along the normal to opacity < 0.5), the gaps (path
//   points outside the silhouette), the widest gap as a fraction of the stroke's width, and the
//   coefficient of variation of the half-width (billows); a point-like stroke (dot, dab) is
//   measured by its outline's radius around its centre instead.
// - `bodyRatio`: the cloud seen from the side: its vertical thickness over its horizontal width
//   across the path, medians over the path points' columns on the canvas mid-plane.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "app/scene/camera.h"
#include "app/scene/canvas.h"
#include "app/volume/box.h"
#include "app/volume/volume.h"

namespace cb::test {

struct Silhouette {
  int width = 0, height = 0, downscale = 1;  // image size; screen pixels per image pixel
  std::vector<float> opacity;
  // Opacity at a screen position (nearest image pixel; 0 outside).
  float at(glm::vec2 screen_px) const;
};

Silhouette silhouetteOpacity(const Volume& volume, const VoxelBox& box, const Camera& camera,
                             int screen_w, int screen_h, int downscale, glm::ivec4 screen_rect);

struct PathMeasures {
  double width_px = 0;     // 2 × median half-width (point-like: 2 × mean radius), screen px
  double cv = 0;           // coefficient of variation of the half-width (radius)
  double widest_gap = 0;   // longest run of the path with no cloud within width_px / 4, ÷ width_px
  double ends_inside = 0;  // 1 when both path ends are inside the silhouette
  // How far the cloud stops short of the path's farther-out end: the distance from that end to
  // the nearest silhouette pixel, ÷ width_px (0 when both ends are inside; 1 when nothing lies
  // within a width of it).
  double end_shortfall = 0;
  std::vector<float> half_widths;
};

PathMeasures measureAlongPath(const Silhouette& s, const std::vector<glm::vec2>& path,
                              bool point_like);

// Thickness ÷ width of the cloud in world units, seen from the side (density > `threshold`).
double bodyRatio(const Volume& volume, const Camera& camera, const Canvas& canvas, int screen_w,
                 int screen_h, const std::vector<glm::vec2>& path, bool point_like,
                 float threshold = 0.1f);

// The path resampled every `step` screen pixels of arc length (the ends kept).
std::vector<glm::vec2> resamplePath(const std::vector<glm::vec2>& path, float step);

}  // namespace cb::test
