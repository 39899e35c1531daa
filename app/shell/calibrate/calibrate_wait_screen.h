// Waiting for the pen: a dark red screen that says the tablet is not connected yet, why (the pen
// source's status), and what to do; done when the pen source connects, or fails when it cannot
// (no permission, a replay that ended).
#pragma once

#include <functional>
#include <string>

#include "app/shell/calibrate/calibrate_screen.h"

namespace cb {

class CalibrateWaitScreen : public CalibrateScreen {
 public:
  // on_done(true, "") once connected; on_done(false, why) when the pen cannot come.
  CalibrateWaitScreen(CalibrateContext& context,
                      std::function<void(bool connected, const std::string& why)> on_done)
      : CalibrateScreen(context), on_done_(std::move(on_done)) {}
  const char* name() const override { return "calibrate-wait"; }
  // Looks at the pen source now (the flow calls it before routing samples).
  void check();
  std::string update(const FrameContext& frame) override;
  bool needsFrame() const override;
  bool draw(FrameContext& frame, std::string* error) override;

 private:
  std::function<void(bool, const std::string&)> on_done_;
  bool done_ = false;
  std::string drawn_status_;
  bool drawn_ = false;
};

}  // namespace cb
