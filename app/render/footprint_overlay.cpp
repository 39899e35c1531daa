#include "app/render/footprint_overlay.h"

#include <vector>

#include "app/render/shader_program.h"

namespace cb {

FootprintOverlay::~FootprintOverlay() {
  if (footprint_texture_) glDeleteTextures(1, &footprint_texture_);
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
  }
  const float zero = 0.0f;
  glClearTexImage(footprint_texture_, 0, GL_RED, GL_FLOAT, &zero);
}

size_t FootprintOverlay::upload(const Footprint& fp, const FootprintRect& rect) {
  FootprintRect r = rect.clipped(fp.width, fp.height);
  if (r.empty() || fp.width != width_ || fp.height != height_) return 0;
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, fp.width);
  glTextureSubImage2D(footprint_texture_, 0, r.x0, r.y0, r.width(), r.height(), GL_RED, GL_FLOAT,
                      fp.values.data() + size_t(r.y0) * fp.width + r.x0);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  return size_t(r.width()) * r.height();
}

void FootprintOverlay::draw(GLuint scene_texture, GLuint target_fbo, int width, int height,
                            const OverlayCursor& cursor, const OverlayStyle& style) {
  glBindFramebuffer(GL_FRAMEBUFFER, target_fbo);
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
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
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glUseProgram(0);
}

}  // namespace cb
