#include "app/render/footprint_overlay.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "app/render/shader_program.h"

namespace cb {

FootprintOverlay::~FootprintOverlay() {
  if (footprint_texture_) glDeleteTextures(1, &footprint_texture_);
  if (scene_read_fbo_) glDeleteFramebuffers(1, &scene_read_fbo_);
  if (vao_) glDeleteVertexArrays(1, &vao_);
  if (program_) glDeleteProgram(program_);
}

bool FootprintOverlay::init(std::string* error) {
  program_ = linkProgram({"fullscreen.vert.glsl"}, {"footprint_overlay.frag.glsl"}, error);
  if (!program_) {
    *error = "footprint overlay: " + *error;
    return false;
  }
  glCreateVertexArrays(1, &vao_);
  glCreateFramebuffers(1, &scene_read_fbo_);
  return true;
}

bool FootprintOverlay::copyScene(GLuint scene_texture, int width, int height) {
  GLint w = 0, h = 0;
  glGetTextureLevelParameteriv(scene_texture, 0, GL_TEXTURE_WIDTH, &w);
  glGetTextureLevelParameteriv(scene_texture, 0, GL_TEXTURE_HEIGHT, &h);
  if (w != width || h != height || !scene_read_fbo_) return false;
  glNamedFramebufferTexture(scene_read_fbo_, GL_COLOR_ATTACHMENT0, scene_texture, 0);
  glDisable(GL_SCISSOR_TEST);
  glBlitNamedFramebuffer(scene_read_fbo_, composite_.fbo(), 0, 0, width, height, 0, 0, width,
                         height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  // The composite writes α = 1 (the scene's own α is not shown).
  const float opaque[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE);
  glClearNamedFramebufferfv(composite_.fbo(), GL_COLOR, 0, opaque);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glEnable(GL_SCISSOR_TEST);
  return true;
}

void FootprintOverlay::beginFootprint(int width, int height) {
  if (width != width_ || height != height_ || !footprint_texture_) {
    if (footprint_texture_) glDeleteTextures(1, &footprint_texture_);
    glCreateTextures(GL_TEXTURE_2D, 1, &footprint_texture_);
    glTextureStorage2D(footprint_texture_, 1, GL_R32F, width, height);
    glTextureParameteri(footprint_texture_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(footprint_texture_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(footprint_texture_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(footprint_texture_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    width_ = width;
    height_ = height;
    full_redraw_ = true;
    inked_ = {};
  }
  const float zero = 0.0f;
  glClearTexImage(footprint_texture_, 0, GL_RED, GL_FLOAT, &zero);
  // Only where the previous footprint had ink needs compositing again.
  pending_ = pending_.united(inked_);
  inked_ = {};
}

size_t FootprintOverlay::upload(const Footprint& fp, const FootprintRect& rect) {
  FootprintRect r = rect.clipped(fp.width, fp.height);
  if (r.empty() || fp.width != width_ || fp.height != height_) return 0;
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, fp.width);
  glTextureSubImage2D(footprint_texture_, 0, r.x0, r.y0, r.width(), r.height(), GL_RED, GL_FLOAT,
                      fp.values.data() + size_t(r.y0) * fp.width + r.x0);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  pending_ = pending_.united(r);
  inked_ = inked_.united(r);
  return size_t(r.width()) * r.height();
}

FootprintOverlay::ScreenRect FootprintOverlay::cursorRect(const OverlayCursor& c,
                                                          const OverlayStyle& style) const {
  if (!c.visible || style.cursor_colour.a <= 0.0f) return {0, 0, 0, 0};
  float reach = c.radius_px + style.cursor_width_px + 2.0f;
  return {int(std::floor(c.screen_px.x - reach)), int(std::floor(c.screen_px.y - reach)),
          int(std::ceil(c.screen_px.x + reach)) + 1, int(std::ceil(c.screen_px.y + reach)) + 1};
}

FootprintOverlay::ScreenRect FootprintOverlay::composite(const ScreenRect& rect, int width,
                                                         int height) {
  ScreenRect r{std::max(rect.x0, 0), std::max(rect.y0, 0), std::min(rect.x1, width),
               std::min(rect.y1, height)};
  if (r.x1 <= r.x0 || r.y1 <= r.y0) return {0, 0, 0, 0};
  // GL's scissor box has y up.
  glScissor(r.x0, height - r.y1, r.x1 - r.x0, r.y1 - r.y0);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  last_composited_ += size_t(r.x1 - r.x0) * size_t(r.y1 - r.y0);
  return r;
}

FootprintOverlay::ScreenRect FootprintOverlay::compositeChanges(GLuint scene_texture, int width,
                                                                int height,
                                                                const OverlayCursor& cursor,
                                                                const OverlayStyle& style) {
  if (composite_.width() != width || composite_.height() != height) {
    std::string error;
    if (!composite_.create(width, height, RenderTarget::Format::kRgba8, &error))
      return {0, 0, 0, 0};
    full_redraw_ = true;
  }
  auto same = [](const OverlayStyle& a, const OverlayStyle& b) {
    return a.ink_colour == b.ink_colour && a.ink_opacity == b.ink_opacity &&
           a.cursor_colour == b.cursor_colour && a.cursor_width_px == b.cursor_width_px;
  };
  if (scene_texture != last_scene_ || !same(style, last_style_)) full_redraw_ = true;

  glBindFramebuffer(GL_FRAMEBUFFER, composite_.fbo());
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glEnable(GL_SCISSOR_TEST);
  glUseProgram(program_);
  glBindTextureUnit(0, scene_texture);
  glBindTextureUnit(1, footprint_texture_);
  glUniform1i(glGetUniformLocation(program_, "u_scene"), 0);
  glUniform1i(glGetUniformLocation(program_, "u_footprint"), 1);
  glUniform2f(glGetUniformLocation(program_, "u_target_size"), float(width), float(height));
  glUniform3fv(glGetUniformLocation(program_, "u_ink_colour"), 1, &style.ink_colour.x);
  glUniform1f(glGetUniformLocation(program_, "u_ink_opacity"), style.ink_opacity);
  glUniform2fv(glGetUniformLocation(program_, "u_cursor_px"), 1, &cursor.screen_px.x);
  glUniform1f(glGetUniformLocation(program_, "u_cursor_radius_px"), cursor.radius_px);
  glUniform1f(glGetUniformLocation(program_, "u_cursor_width_px"), style.cursor_width_px);
  glm::vec4 cursor_colour = style.cursor_colour;
  if (!cursor.visible) cursor_colour.a = 0.0f;
  glUniform4fv(glGetUniformLocation(program_, "u_cursor_colour"), 1, &cursor_colour.x);
  glBindVertexArray(vao_);

  last_composited_ = 0;
  const ScreenRect new_cursor = cursorRect(cursor, style);
  ScreenRect box{0, 0, 0, 0};
  const auto grow = [&box](const ScreenRect& r) {
    if (r.x1 <= r.x0 || r.y1 <= r.y0) return;
    box = box.x1 <= box.x0 ? r
                           : ScreenRect{std::min(box.x0, r.x0), std::min(box.y0, r.y0),
                                        std::max(box.x1, r.x1), std::max(box.y1, r.y1)};
  };
  if (full_redraw_ && inked_.empty() && copyScene(scene_texture, width, height)) {
    // No ink on the footprint: the frame is the scene, copied, with the cursor drawn over it
    // (a copy costs a fraction of the shader's pass over every pixel on llvmpipe).
    grow({0, 0, width, height});
    grow(composite(new_cursor, width, height));
  } else if (full_redraw_) {
    grow(composite({0, 0, width, height}, width, height));
  } else {
    // The uploaded footprint texels, in screen pixels (+2 for the bilinear footprint lookup).
    if (!pending_.empty() && width_ > 0 && height_ > 0) {
      float sx = float(width) / float(width_), sy = float(height) / float(height_);
      grow(composite({int(std::floor(pending_.x0 * sx)) - 2, int(std::floor(pending_.y0 * sy)) - 2,
                      int(std::ceil(pending_.x1 * sx)) + 2, int(std::ceil(pending_.y1 * sy)) + 2},
                     width, height));
    }
    grow(composite(last_cursor_, width, height));  // erase the old one
    grow(composite(new_cursor, width, height));
  }
  glDisable(GL_SCISSOR_TEST);
  glBindVertexArray(0);
  glUseProgram(0);
  full_redraw_ = false;
  last_scene_ = scene_texture;
  last_style_ = style;
  last_cursor_ = new_cursor;
  pending_ = {};
  return box;
}

void FootprintOverlay::draw(GLuint scene_texture, GLuint target_fbo, int width, int height,
                            const OverlayCursor& cursor, const OverlayStyle& style) {
  compositeChanges(scene_texture, width, height, cursor, style);
  if (composite_.width() != width || composite_.height() != height) return;
  glBlitNamedFramebuffer(composite_.fbo(), target_fbo, 0, 0, width, height, 0, 0, width, height,
                         GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, target_fbo);
}

glm::ivec4 FootprintOverlay::drawChanges(GLuint scene_texture, GLuint target_fbo, int width,
                                         int height, const OverlayCursor& cursor,
                                         const OverlayStyle& style) {
  const ScreenRect r = compositeChanges(scene_texture, width, height, cursor, style);
  glBindFramebuffer(GL_FRAMEBUFFER, target_fbo);
  if (r.x1 <= r.x0 || r.y1 <= r.y0) return glm::ivec4(0);
  // Blit coordinates have y up.
  glBlitNamedFramebuffer(composite_.fbo(), target_fbo, r.x0, height - r.y1, r.x1, height - r.y0,
                         r.x0, height - r.y1, r.x1, height - r.y0, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  return {r.x0, r.y0, r.x1, r.y1};
}

}  // namespace cb
