// The fit's result: each target's cross with where its tap lands after the new correction and
// the residual in pixels beside it, the largest and rms error, whether that is good, and what to
// do next: tap the green Accept box (or press Space) to save, the orange Redo box to tap the
// targets again, Esc to leave without saving. A choice is a pen tap (down and up) in a box.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "app/shell/calibrate/calibrate_screen.h"
#include "calibration/n_point_calibration.h"

namespace cb {

class CalibrateResultScreen : public CalibrateScreen {
 public:
  enum class Choice { kAccept, kRedo };
  // `area_to_screen`: tablet mm → screen px by the area mapping alone (what the fit corrects).
  // `auto_accept`: accept after the screen was shown once (unattended runs).
  CalibrateResultScreen(CalibrateContext& context, CalibrationFit fit, std::vector<Tap> taps,
                        const glm::dmat3& area_to_screen, bool auto_accept,
                        std::function<void(Choice)> on_done);
  const char* name() const override { return "calibrate-result"; }
  void onPenEvent(const CalibratePenEvent& e) override;
  void onCommand(Command command, int64_t t_ns) override;
  std::string update(const FrameContext& frame) override;
  bool draw(FrameContext& frame, std::string* error) override;
  void presented(const FrameContext& frame, double frame_ms) override;
  // The boxes on a width × height screen: between the middle and bottom rows of targets.
  static CalibrateBox acceptBox(int width, int height);
  static CalibrateBox redoBox(int width, int height);

 private:
  void choose(Choice choice);
  CalibrationFit fit_;
  std::vector<Tap> taps_;
  glm::dmat3 area_to_screen_;
  bool auto_accept_;
  std::function<void(Choice)> on_done_;
  bool shown_ = false, chosen_ = false;
};

}  // namespace cb
