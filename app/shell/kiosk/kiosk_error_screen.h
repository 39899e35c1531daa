// What the kiosk shows instead of exiting when it cannot start as configured: a bad config file
// (kiosk.toml, kiosk/texts.toml, render.toml, mapping.toml, brush.toml), a data dir it cannot use.
// Exiting would restart-loop under `Restart=always` into a blank screen; this plain screen names
// the file and line and what to do, stays up (the service's READY and watchdog pings carry on,
// so systemd does not restart it) and ends only when the service is stopped or restarted. The
// same text goes to the log (the system journal).
#pragma once

#include <string>

#include "app/shell/screen.h"
#include "app/shell/ui_overlay.h"

namespace cb {

class KioskErrorScreen : public Screen {
 public:
  // `problem`: "FILE:LINE: what" or "DIR: what".
  explicit KioskErrorScreen(std::string problem) : problem_(std::move(problem)) {}
  const char* name() const override { return "kiosk error"; }
  void onCommand(Command, int64_t) override {}
  bool onKey(const DisplayEvent&, int64_t) override { return true; }  // no way out but the unit
  // Drawn again for its first frames and after a resize (a window mapped or made fullscreen
  // after the first frame would otherwise stay blank); then it only waits.
  bool needsFrame() const override { return frames_drawn_ < kFramesToDraw; }
  void onResize(int, int) override { frames_drawn_ = 0; }
  bool draw(FrameContext& frame, std::string* error) override;
  bool allowsQuit() const override { return false; }
  const std::string& problem() const { return problem_; }
  // The lines drawn (tests read them).
  static std::string title() { return "cloudbrush kiosk cannot start"; }
  static std::string hint();

 private:
  std::string problem_;
  UiOverlay ui_;
  bool ui_ready_ = false;
  int frames_drawn_ = 0;
  static constexpr int kFramesToDraw = 30;
};

}  // namespace cb
