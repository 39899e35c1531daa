// Tapping the targets of the N-point calibration (calibration/n_point_calibration.h): one cross
// at a time, with "Tap the centre of the cross with the pen (k of N)" and a bar of progress;
// taps already made stay as small green crosses. A tap is a pen down and up (pen events, from
// the calibrated contact) that did not slide; a refused tap says why on the screen.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "app/shell/calibrate/calibrate_screen.h"
#include "calibration/n_point_calibration.h"

namespace cb {

class CalibrateTargetsScreen : public CalibrateScreen {
 public:
  // `on_done` gets one tap per target, in the targets' order.
  CalibrateTargetsScreen(CalibrateContext& context, std::vector<glm::dvec2> targets,
                         std::function<void(const std::vector<Tap>&)> on_done)
      : CalibrateScreen(context), targets_(std::move(targets)), on_done_(std::move(on_done)) {}
  const char* name() const override { return "calibrate-targets"; }
  // Forgets the taps made so far (redo).
  void restart();
  void onPenEvent(const CalibratePenEvent& e) override;
  bool draw(FrameContext& frame, std::string* error) override;
  size_t tapsMade() const { return taps_.size(); }

 private:
  std::vector<glm::dvec2> targets_;
  std::function<void(const std::vector<Tap>&)> on_done_;
  TapCollector collector_;
  std::vector<Tap> taps_;
  std::string problem_;  // why the last tap was refused
};

}  // namespace cb
