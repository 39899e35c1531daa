// What the painter's heads-up overlay shows, as HudItems (app/render/hud_overlay.h), computed on
// the CPU from plain data so tests can predict every pixel:
//   S  ray-sample statistics of the last ray cast (thesis §4.4's cost per pixel): the histogram
//      of samples per pixel as bars, with total, mean and max samples as digits;
//   C  the circles the hybrid mapping grew for the last stroke (thesis §6.3), as rings where
//      they were grown in the paint view;
//   while the pen is in range: the outline of the screen region where the canvas slab meets the
//      volume (thesis §3.4), i.e. where a stroke can land in the volume at all.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "app/mapping/circle_growth.h"
#include "app/render/hud_overlay.h"
#include "app/render/volume_renderer.h"
#include "app/scene/camera.h"
#include "app/scene/canvas.h"
#include "app/scene/drawable_region.h"

namespace cb {

// Where the statistics panel's bars sit (integer pixels, so a bar of height h covers exactly h
// pixel rows above `baseline_y`).
struct StatsPanelLayout {
  int left = 24;       // x of bar 0
  int baseline_y = 0;  // bars grow upwards from here (pixel rows baseline_y - h .. baseline_y-1)
  int bar_width = 6;
  int bar_pitch = 8;     // bar i starts at left + i * bar_pitch
  int max_height = 120;  // the fullest bin's bar
};
StatsPanelLayout statsPanelLayout(int screen_width, int screen_height);
// Bar height of each histogram bin: round(count / max count × max_height).
std::vector<int> statsBarHeights(const std::vector<uint32_t>& histogram, int max_height);

inline const glm::vec4 kHudBarColour{1.0f, 0.78f, 0.16f, 1.0f};
inline const glm::vec4 kHudRingColour{1.0f, 0.0f, 1.0f, 1.0f};
inline const glm::vec4 kHudDigitColour{1.0f, 1.0f, 1.0f, 1.0f};
inline const glm::vec4 kHudCanvasColour{0.6f, 0.9f, 1.0f, 0.45f};

// Digits (and '.', '-', ' ') of a 3×5 cell font, each lit cell a `cell`-pixel square, starting
// at (x, y) top-left. Other characters are drawn as a blank.
void appendHudText(const std::string& text, int x, int y, int cell, glm::vec4 colour,
                   std::vector<HudItem>* items);

// The S panel: nothing when `stats` has no samples (collect_stats was off).
void appendStatsPanel(const RenderStats& stats, int screen_width, int screen_height,
                      std::vector<HudItem>* items);

// The C rings: circle centres and radii are footprint pixels (pixel (x, y) centred at (x, y));
// the footprint is stretched over the screen, so footprint pixel x covers screen
// [x·s, (x+1)·s) with s = screen / footprint size.
glm::vec2 footprintToScreen(glm::vec2 footprint_px, int footprint_w, int footprint_h, int screen_w,
                            int screen_h);
void appendCircleRings(const std::vector<Circle>& circles, int footprint_w, int footprint_h,
                       int screen_w, int screen_h, std::vector<HudItem>* items);

// The screen outline (convex, y down, in order) of the part of the volume's world box inside
// the canvas slab, seen by `camera`; empty when the slab misses the box or a corner is behind
// the camera's near plane.
std::vector<glm::vec2> canvasRegionOutline(const Camera& camera, const Canvas& canvas,
                                           glm::vec3 world_min, glm::vec3 world_max, int screen_w,
                                           int screen_h);
// A veil over the screen outside the drawable region (4-pixel row bands), so ink drawn where it
// cannot land looks different at once.
void appendOutsideVeil(const DrawableRegion& region, std::vector<HudItem>* items);
// Grid lines on the canvas mid-plane across the box's x/z extent, `divisions` per side, each
// line drawn cell by cell as projected by `to_screen` (world → screen pixels; x < -1e5 behind
// the camera), leaving out the cells with an end behind the camera.
void appendCanvasGrid(const Canvas& canvas, glm::vec3 box_min, glm::vec3 box_max, int divisions,
                      const std::function<glm::vec2(glm::vec3)>& to_screen,
                      std::vector<HudItem>* items);
// The Vacuum's location aid (thesis §3.5.1, Fig. 3.5: "intersecting grids from three
// axis-aligned planes"): grids on the planes x = centre.x, y = centre.y and z = centre.z across
// the box, `divisions` cells per side, red, green and blue; lines with an end behind the camera
// (to_screen gives x < -1e5) are left out.
void appendAxisPlaneGrids(glm::vec3 centre, glm::vec3 box_min, glm::vec3 box_max, int divisions,
                          const std::function<glm::vec2(glm::vec3)>& to_screen,
                          std::vector<HudItem>* items);
void appendCanvasOutline(const std::vector<glm::vec2>& outline, std::vector<HudItem>* items);

}  // namespace cb
