#include "app/shell/kiosk/reconnect_screen.h"

#include <algorithm>

#include "app/render/gl/gl.h"

namespace cb {

void ReconnectScreen::setTexts(std::string title, std::string hint, std::string detail) {
  title_ = std::move(title);
  hint_ = std::move(hint);
  detail_ = std::move(detail);
}

bool ReconnectScreen::draw(FrameContext& frame, std::string* error) {
  (void)error;
  if (!ui_) return true;
  const float w = float(frame.width), h = float(frame.height);
  std::vector<UiLabel> labels;
  labels.push_back({0.5f * w, 0.34f * h, title_, 0.08f * h, 0xffd266ffu, true, 0x101820e8u});
  labels.push_back(
      {0.5f * w, 0.5f * h, hint_, std::max(16.0f, 0.035f * h), 0xffffffffu, true, 0x101820e0u});
  if (!detail_.empty())
    labels.push_back(
        {0.5f * w, 0.6f * h, detail_, std::max(14.0f, 0.022f * h), 0xb8c4d0ffu, true, 0x101820d0u});
  glBindFramebuffer(GL_FRAMEBUFFER, frame.display.framebuffer());
  glViewport(0, 0, frame.width, frame.height);
  ui_->drawLabels(frame.width, frame.height, labels);
  return true;
}

}  // namespace cb
