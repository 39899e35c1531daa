// The painter's heads-up overlay: a small GL pass that draws flat items over a finished frame —
// solid rectangles (bars, digit cells, panels), rings (the mapping's circles) and line segments
// (outlines) — all in screen pixels with y down, alpha-blended over what is there. One instanced
// draw from a storage buffer; what to draw is decided by the caller (the painter builds its items
// in the shell, which includes this header — never the other way).
//
//   HudOverlay hud;
//   hud.init(&error);                                 // current GL 4.5 core context
//   hud.draw(display.framebuffer(), 1280, 720, items);
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "app/render/gl/gl.h"

namespace cb {

// One item; use the make* helpers. Layout matches HudItem in shaders/hud.*.glsl (std430).
struct HudItem {
  glm::vec4 rect{0.0f};    // bounding rectangle x0, y0, x1, y1 (pixels, y down)
  glm::vec4 colour{1.0f};  // RGBA, straight alpha
  glm::vec4 p0{0.0f};
  glm::vec4 p1{0.0f};
};

// A filled rectangle [x0, x1) × [y0, y1): with integer edges exactly those pixels.
HudItem makeHudRect(float x0, float y0, float x1, float y1, glm::vec4 colour);
// A ring of `width` pixels around the circle (centre, radius).
HudItem makeHudRing(glm::vec2 centre, float radius, float width, glm::vec4 colour);
// A line segment a–b, `width` pixels wide, with round ends.
HudItem makeHudSegment(glm::vec2 a, glm::vec2 b, float width, glm::vec4 colour);

class HudOverlay {
 public:
  HudOverlay() = default;
  ~HudOverlay();
  HudOverlay(const HudOverlay&) = delete;
  HudOverlay& operator=(const HudOverlay&) = delete;

  bool init(std::string* error);
  // Blends `items` (in order, later on top) over `target_fbo` of width × height pixels; with
  // `box` (x0, y0, x1, y1; pixels, y down, half-open) only over those pixels, each as the whole
  // draw blends it (the painter's late ink redraws the HUD over the ink it re-blitted).
  void draw(GLuint target_fbo, int width, int height, const std::vector<HudItem>& items,
            const glm::ivec4* box = nullptr);

 private:
  GLuint program_ = 0, vao_ = 0, buffer_ = 0;
  GLint viewport_location_ = -1;
  size_t capacity_ = 0;  // items the buffer holds
};

}  // namespace cb
