// The participant's press (calibration/pressure_range.h): "press lightly and hold", then "press
// firmly and hold", each until the bar is full, then lift. A pale box asks for the light press, a
// deep blue one for the firm press. Contact comes from the pen events (the calibrated
// hysteresis), pressure from the nib-offset-corrected sample. A press that cannot be fitted
// (firm not firmer than light) says why and starts over.
#pragma once

#include <functional>
#include <string>

#include "app/shell/calibrate/calibrate_screen.h"
#include "calibration/pressure_range.h"

namespace cb {

class CalibratePressureScreen : public CalibrateScreen {
 public:
  // `on_done` gets the fit once both presses were made and it has a range.
  CalibratePressureScreen(CalibrateContext& context, float light_target,
                          std::function<void(const PressureRangeFit&)> on_done)
      : CalibrateScreen(context), collector_(100, light_target), on_done_(std::move(on_done)) {}
  const char* name() const override { return "calibrate-pressure"; }
  void onPenEvent(const CalibratePenEvent& e) override;
  bool draw(FrameContext& frame, std::string* error) override;
  PressureRangeCollector::Step step() const { return collector_.step(); }

 private:
  PressureRangeCollector collector_;
  std::function<void(const PressureRangeFit&)> on_done_;
  std::string problem_;  // why the last attempt was refused
};

}  // namespace cb
