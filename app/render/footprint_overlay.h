// The live footprint overlay of painting mode (thesis §3.3: while painting the camera is still,
// so the rendered volume is cached and only the footprint and the cursor are redrawn each frame).
// The footprint lives in an R32F texture; each brush call's changed rectangle is uploaded alone,
// so a sample shows in the next frame at the cost of its rectangle, not of the whole footprint.
// The composited frame is kept in an offscreen target and only the regions that changed (the
// uploaded rectangles and the old and new cursor) are composited again, with scissored draws;
// the frame is then blitted to the caller's framebuffer. On llvmpipe a full-screen composite
// costs tens of ms, the incremental one about a blit (≈1 ms at 1280×720).
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
#include "app/render/render_target.h"

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
  // row 0 at the bottom, as a RenderTarget's texture is. Only changed regions are composited
  // again; a different scene texture, size or style composites everything.
  void draw(GLuint scene_texture, GLuint target_fbo, int width, int height,
            const OverlayCursor& cursor, const OverlayStyle& style = {});
  // Late ink: composites what changed since the last draw (footprint texels uploaded since, the
  // old and new cursor) and blits only the box around it to `target_fbo`; the rest of the
  // target keeps the last draw's pixels. Returns that box (x0, y0, x1, y1; pixels, y down,
  // half-open; all 0 when nothing changed), the whole frame when everything was composited.
  glm::ivec4 drawChanges(GLuint scene_texture, GLuint target_fbo, int width, int height,
                         const OverlayCursor& cursor, const OverlayStyle& style = {});
  // Forces the next draw to composite the whole frame (call after re-rendering the scene into
  // the same texture).
  void invalidate() { full_redraw_ = true; }
  // Pixels composited by the last draw (for benchmarks and tests).
  size_t lastCompositedPixels() const { return last_composited_; }
  int footprintWidth() const { return width_; }
  int footprintHeight() const { return height_; }

 private:
  struct ScreenRect {
    int x0, y0, x1, y1;  // y down, half-open
  };
  // One scissored draw of the composite shader over `r`; returns `r` clipped to the target.
  ScreenRect composite(const ScreenRect& r, int width, int height);
  // Composites what changed into composite_ (everything after invalidate() or a new scene or
  // style); returns the box around what was composited.
  ScreenRect compositeChanges(GLuint scene_texture, int width, int height,
                              const OverlayCursor& cursor, const OverlayStyle& style);
  ScreenRect cursorRect(const OverlayCursor& cursor, const OverlayStyle& style) const;
  // The scene texture copied into composite_ whole (α set to 1), for a full redraw with no ink;
  // false when it is not the target's size.
  bool copyScene(GLuint scene_texture, int width, int height);

  GLuint program_ = 0, vao_ = 0, footprint_texture_ = 0;
  GLuint scene_read_fbo_ = 0;  // reads the scene texture for copyScene
  int width_ = 0, height_ = 0;
  RenderTarget composite_;
  bool full_redraw_ = true;
  GLuint last_scene_ = 0;
  OverlayStyle last_style_;
  FootprintRect pending_;  // footprint texels changed since the last draw
  FootprintRect inked_;    // texels uploaded since beginFootprint (cleared by the next one)
  ScreenRect last_cursor_{0, 0, 0, 0};
  size_t last_composited_ = 0;
};

}  // namespace cb
