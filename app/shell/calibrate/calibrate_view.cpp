#include "app/shell/calibrate/calibrate_view.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/render/gl/gl.h"

namespace cb {

void CalibrateView::begin(unsigned framebuffer, int width, int height, glm::vec3 background) {
  framebuffer_ = framebuffer;
  width_ = width;
  height_ = height;
  items_.clear();
  labels_.clear();
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, width, height);
  glDisable(GL_SCISSOR_TEST);
  glClearColor(background.r, background.g, background.b, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
}

void CalibrateView::rect(double x, double y, double w, double h, glm::vec3 colour) {
  // Whole pixels, so a box covers exactly the pixels it names.
  items_.push_back(makeHudRect(float(std::floor(x)), float(std::floor(y)), float(std::ceil(x + w)),
                               float(std::ceil(y + h)), glm::vec4(colour, 1.0f)));
}

void CalibrateView::crosshair(glm::dvec2 c, double arm, glm::vec3 colour) {
  rect(c.x - arm, c.y - 1, 2 * arm, 3, colour);
  rect(c.x - 1, c.y - arm, 3, 2 * arm, colour);
}

void CalibrateView::cursor(glm::dvec2 at) {
  rect(at.x - 2, at.y - 2, 5, 5, {0.9f, 0.9f, 1.0f});
}

float CalibrateView::bodySize() const {
  return std::max(18.0f, float(height_) / 30.0f);
}

void CalibrateView::label(float x, float y, const std::string& text, float size_px, uint32_t rgba,
                          bool centred) {
  labels_.push_back({x, y, text, size_px > 0.0f ? size_px : bodySize(), rgba, centred});
}

void CalibrateView::say(const std::vector<std::string>& lines, float top) {
  const float size = bodySize();
  for (size_t i = 0; i < lines.size(); ++i)
    label(float(width_) * 0.5f, float(height_) * top + float(i) * size * 1.5f, lines[i],
          i == 0 ? size * 1.3f : size, i == 0 ? 0xffffffffu : 0xd0d8e0ffu, true);
}

std::vector<std::string> CalibrateView::words() const {
  std::vector<std::string> lines;
  for (const UiLabel& l : labels_) lines.push_back(l.text);
  return lines;
}

bool CalibrateView::finish(std::string* error) {
  if (!items_.empty()) {
    if (!hud_ready_) {
      if (!hud_.init(error)) return false;
      hud_ready_ = true;
    }
    hud_.draw(framebuffer_, width_, height_, items_);
  }
  if (!labels_.empty() && !ui_failed_) {
    if (!ui_ready_) {
      std::string why;
      if (!ui_.init(&why)) {
        // Keys and the pen still work; the boxes and targets still show.
        std::fprintf(stderr, "calibrate: on-screen text unavailable: %s\n", why.c_str());
        ui_failed_ = true;
        return true;
      }
      ui_ready_ = true;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    glViewport(0, 0, width_, height_);
    ui_.drawLabels(width_, height_, labels_);
  }
  return true;
}

}  // namespace cb
