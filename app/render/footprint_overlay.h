// The live footprint overlay of painting mode (thesis §3.3: while painting the camera is still,
// so the rendered volume is cached and only the footprint and the cursor are redrawn each frame).
// The footprint lives in an R32F texture; each brush call's changed rectangle is uploaded alone,
// so a sample shows in the next frame at the cost of its rectangle, not of the whole footprint.
//
//   FootprintOverlay overlay;
//   overlay.init(&error);                       // current GL 4.5 core context
//   overlay.beginFootprint(w, h);               // at tip-down (clears)
//   overlay.upload(engine.footprint(), rect);   // after each sample
//   overlay.draw(scene_texture, fbo, 1280, 720, cursor);
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "app/brush/footprint_rect.h"
#include "app/brush/stroke_result.h"
#include "app/render/gl/gl.h"

namespace cb {

struct OverlayStyle {
  glm::vec3 ink_colour{1.0f, 1.0f, 1.0f};
  float ink_opacity = 0.85f;
  glm::vec4 cursor_colour{0.1f, 0.1f, 0.1f, 1.0f};  // alpha 0 hides the cursor
  float cursor_width_px = 1.5f;
};

struct OverlayCursor {
  glm::vec2 screen_px{0.0f};  // y down
  float radius_px = 8.0f;
  bool visible = true;
};

class FootprintOverlay {
 public:
  FootprintOverlay() = default;
  ~FootprintOverlay();
  FootprintOverlay(const FootprintOverlay&) = delete;
  FootprintOverlay& operator=(const FootprintOverlay&) = delete;

  bool init(std::string* error);
  // (Re)allocates the footprint texture at width × height footprint pixels and clears it.
  void beginFootprint(int width, int height);
  // Uploads `rect` of `footprint` (same size as beginFootprint); an empty rect uploads nothing.
  // Returns the number of texels uploaded.
  size_t upload(const Footprint& footprint, const FootprintRect& rect);
  // Draws scene + footprint + cursor into `target_fbo` (width × height pixels). The footprint is
  // stretched over the target (footprint_scale ≠ 1 works). `scene_texture` is sampled with its
  // row 0 at the bottom, as a RenderTarget's texture is.
  void draw(GLuint scene_texture, GLuint target_fbo, int width, int height,
            const OverlayCursor& cursor, const OverlayStyle& style = {});
  int footprintWidth() const { return width_; }
  int footprintHeight() const { return height_; }

 private:
  GLuint program_ = 0, vao_ = 0, footprint_texture_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace cb
