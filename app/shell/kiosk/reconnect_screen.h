// The kiosk's "reconnect the pen" screen: the tablet was unplugged while a visitor
// painted. Drawn over the visitor's frame (their cloud stays visible and is kept): a veil and two
// lines saying what happened and what to do. The kiosk screen shows it while the pen source
// reports no connection and returns to painting when it reconnects.
#pragma once

#include <string>

#include "app/shell/screen.h"
#include "app/shell/ui_overlay.h"

namespace cb {

class ReconnectScreen : public Screen {
 public:
  explicit ReconnectScreen(UiOverlay* ui) : ui_(ui) {}
  const char* name() const override { return "reconnect"; }
  void onCommand(Command, int64_t) override {}
  void setTexts(std::string title, std::string hint, std::string detail);
  // Draws over what the framebuffer holds.
  bool draw(FrameContext& frame, std::string* error) override;

 private:
  UiOverlay* ui_;
  std::string title_, hint_, detail_;
};

}  // namespace cb
