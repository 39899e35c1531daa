// What the calibration screens draw with: a background colour, flat rectangles and crosshairs
// (the HUD pass, app/render/hud_overlay.h) and words (the shell's one font, ui_overlay.h). A
// frame is collected with the add* calls and drawn by finish(), y down in framebuffer pixels.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "app/render/hud_overlay.h"
#include "app/shell/ui_overlay.h"

namespace cb {

// A pen target on a calibration screen (the result screen's Accept and Redo boxes).
struct CalibrateBox {
  double x = 0, y = 0, w = 0, h = 0;
  bool contains(glm::dvec2 p) const { return p.x >= x && p.x < x + w && p.y >= y && p.y < y + h; }
};

class CalibrateView {
 public:
  // Starts a frame of width × height over `framebuffer`, cleared to `background`.
  void begin(unsigned framebuffer, int width, int height, glm::vec3 background);
  void rect(double x, double y, double w, double h, glm::vec3 colour);
  void box(const CalibrateBox& b, glm::vec3 colour) { rect(b.x, b.y, b.w, b.h, colour); }
  void crosshair(glm::dvec2 centre, double arm, glm::vec3 colour);
  // The pen's position: a small light square.
  void cursor(glm::dvec2 at);
  // A line of words; `centred` centres it on x. size_px 0: the screen's body size.
  void label(float x, float y, const std::string& text, float size_px = 0.0f,
             uint32_t rgba = 0xffffffffu, bool centred = true);
  // A title and lines below it, centred, starting at `top` of the screen height: what the
  // screen waits for and what to do.
  void say(const std::vector<std::string>& lines, float top = 0.12f);
  float bodySize() const;
  // Draws the frame; false with *error when the GL passes cannot start.
  bool finish(std::string* error);
  // The words of the frame last drawn, one line each (what a person reads on it).
  std::vector<std::string> words() const;

 private:
  HudOverlay hud_;
  UiOverlay ui_;
  bool hud_ready_ = false, ui_ready_ = false, ui_failed_ = false;
  unsigned framebuffer_ = 0;
  int width_ = 0, height_ = 0;
  std::vector<HudItem> items_;
  std::vector<UiLabel> labels_;
};

}  // namespace cb
