// Where a picture or model cloud goes: seen from a camera (the current paint view), centred on
// the point where the view's centre ray meets the canvas mid-plane (thesis §3.4; the plane facing
// the camera through the volume centre at canvas altitude when the ray misses it, as the
// mapping's fallback, §6.5), sized to a fraction of the view.
#pragma once

#include <glm/glm.hpp>

#include "app/mapping/paint_view_geometry.h"
#include "app/scene/camera.h"
#include "app/scene/canvas.h"
#include "app/volume/sky_extent.h"
#include "app/volume/volume.h"

namespace cb {

struct ToolView {
  Camera camera;
  int view_width = 1280, view_height = 720;
  Canvas canvas;
  // The picture (or the model's projected bounding box) fills this fraction of the view's
  // shorter fitting side.
  float size_fraction = 0.5f;
};

// The placement of one picture of width×height pixels: picture pixel coordinates (continuous,
// (0,0) the top-left corner) → view pixel coordinates → rays, and the camera-facing plane
// through the anchor on which the picture's particles are stretched into depth.
class PicturePlacement {
 public:
  PicturePlacement(const ToolView& view, const Volume& volume, int picture_width,
                   int picture_height);

  glm::vec3 anchor() const { return anchor_; }
  glm::vec3 forward() const { return geometry_.forward(); }
  // View pixels per picture pixel.
  float scale() const { return scale_; }
  // Continuous picture coordinates → continuous view coordinates ((0,0) = top-left corner).
  glm::vec2 toView(glm::vec2 picture) const { return origin_ + picture * scale_; }
  // World length of one picture pixel at the anchor's depth.
  float pictureTexelWorldSize() const;
  // The world point seen at continuous picture coordinates `picture`, `depth_offset` world units
  // in front of (< 0) or behind (> 0) the anchor plane along the view axis.
  glm::vec3 worldPoint(glm::vec2 picture, float depth_offset) const;

 private:
  PaintViewGeometry geometry_;
  glm::vec3 anchor_;
  float anchor_depth_;
  float scale_;
  glm::vec2 origin_;
};

// The anchor alone: the view's centre ray on the canvas mid-plane (or the fallback plane).
glm::vec3 toolAnchor(const ToolView& view, const Volume& volume);

// A placement's reach — the box of `volume`'s voxel grid a tool writes only inside, before it is
// clipped to the volume (picture_cloud.h pictureReach, model_cloud.h modelReach) — as the world
// x/z rectangle the sky must hold (sky_extent.h): the box's outer voxel faces. An empty box writes
// nothing; one whose faces are not finite (a degenerate view) is not bounded, and the sky then
// grows as far as it may, as for a stroke whose rays miss the canvas.
SkyReach placementReach(const VoxelBox& voxels, const Volume& volume);

}  // namespace cb
