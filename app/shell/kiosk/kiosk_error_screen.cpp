#include "app/shell/kiosk/kiosk_error_screen.h"

#include <algorithm>
#include <vector>

#include "app/render/gl/display.h"
#include "app/render/gl/gl.h"

namespace cb {

std::string KioskErrorScreen::hint() {
  return "Fix the file named above (the shipped defaults are in /usr/share/cloudbrush/config;\n"
         "your changes go in /etc/cloudbrush), then: systemctl restart cloudbrush-kiosk";
}

bool KioskErrorScreen::draw(FrameContext& frame, std::string* error) {
  if (!ui_ready_) {
    ui_.addGlyphs(problem_);
    if (!ui_.init(error)) return false;
    ui_ready_ = true;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, frame.display.framebuffer());
  glViewport(0, 0, frame.width, frame.height);
  glClearColor(0.10f, 0.05f, 0.05f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  const float w = float(frame.width), h = float(frame.height);
  const float big = std::max(22.0f, 0.05f * h), line = std::max(14.0f, 0.03f * h);
  const float x = 0.08f * w, wrap = 0.84f * w;
  std::vector<UiLabel> labels;
  labels.push_back({x, 0.12f * h, title(), big, 0xff8080ffu, false, 0, 0.0f});
  labels.push_back({x, 0.24f * h, problem_, line, 0xffffffffu, false, 0, wrap});
  labels.push_back({x, 0.62f * h, hint(), line, 0xb8c4d0ffu, false, 0, wrap});
  ui_.drawLabels(frame.width, frame.height, labels);
  ++frames_drawn_;
  return true;
}

}  // namespace cb
