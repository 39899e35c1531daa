#include "app/render/hud_overlay.h"

#include <algorithm>

#include "app/render/shader_program.h"

namespace cb {

HudItem makeHudRect(float x0, float y0, float x1, float y1, glm::vec4 colour) {
  HudItem item;
  item.rect = {x0, y0, x1, y1};
  item.colour = colour;
  return item;
}

HudItem makeHudRing(glm::vec2 centre, float radius, float width, glm::vec4 colour) {
  const float reach = radius + width;
  HudItem item;
  item.rect = {centre.x - reach, centre.y - reach, centre.x + reach, centre.y + reach};
  item.colour = colour;
  item.p0 = {1.0f, centre.x, centre.y, radius};
  item.p1 = {width, 0.0f, 0.0f, 0.0f};
  return item;
}

HudItem makeHudSegment(glm::vec2 a, glm::vec2 b, float width, glm::vec4 colour) {
  const glm::vec2 lo = glm::min(a, b) - glm::vec2(width), hi = glm::max(a, b) + glm::vec2(width);
  HudItem item;
  item.rect = {lo.x, lo.y, hi.x, hi.y};
  item.colour = colour;
  item.p0 = {2.0f, a.x, a.y, 0.0f};
  item.p1 = {width, b.x, b.y, 0.0f};
  return item;
}

HudOverlay::~HudOverlay() {
  if (program_) glDeleteProgram(program_);
  if (vao_) glDeleteVertexArrays(1, &vao_);
  if (buffer_) glDeleteBuffers(1, &buffer_);
}

bool HudOverlay::init(std::string* error) {
  if (program_) return true;
  program_ = linkProgram({"hud.vert.glsl"}, {"hud.frag.glsl"}, error);
  if (!program_) {
    *error = "HUD overlay: " + *error;
    return false;
  }
  viewport_location_ = glGetUniformLocation(program_, "u_viewport");
  glCreateVertexArrays(1, &vao_);
  return true;
}

void HudOverlay::draw(GLuint target_fbo, int width, int height, const std::vector<HudItem>& items,
                      const glm::ivec4* box) {
  if (items.empty() || !program_) return;
  if (box && (box->z <= box->x || box->w <= box->y)) return;
  if (items.size() > capacity_) {
    if (buffer_) glDeleteBuffers(1, &buffer_);
    capacity_ = std::max<size_t>(items.size(), 256);
    glCreateBuffers(1, &buffer_);
    glNamedBufferStorage(buffer_, GLsizeiptr(capacity_ * sizeof(HudItem)), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
  }
  glNamedBufferSubData(buffer_, 0, GLsizeiptr(items.size() * sizeof(HudItem)), items.data());
  glBindFramebuffer(GL_FRAMEBUFFER, target_fbo);
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  if (box) {  // GL's scissor box has y up
    glEnable(GL_SCISSOR_TEST);
    glScissor(box->x, height - box->w, box->z - box->x, box->w - box->y);
  } else {
    glDisable(GL_SCISSOR_TEST);
  }
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glUseProgram(program_);
  glUniform2f(viewport_location_, float(width), float(height));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer_);
  glBindVertexArray(vao_);
  glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, GLsizei(items.size()));
  glBindVertexArray(0);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
}

}  // namespace cb
