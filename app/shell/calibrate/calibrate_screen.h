// What the calibration screens share: the pen source, the pen input (calibrated samples → pen
// events, pen_events.h), the view they draw with, the journal, and where progress lines go; and
// the base of each screen. A calibration screen is a Screen (screen.h) that reports completion
// through the callback it was made with, so a flow (calibrate_flow_screen.h) or an operator
// panel can push it and go on when it is done.
//
//   calibrate_wait_screen.h      waits for the pen to connect
//   calibrate_pressure_screen.h  the participant's light and firm press
//   calibrate_targets_screen.h   taps on N targets
//   calibrate_result_screen.h    residuals, Accept or Redo
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "app/shell/calibrate/calibrate_pen_input.h"
#include "app/shell/calibrate/calibrate_view.h"
#include "app/shell/screen.h"

namespace cb {

class JournalWriter;
class PenSource;

struct CalibrateContext {
  PenSource* pen = nullptr;  // not owned
  int width = 0, height = 0;
  CalibratePenInput input;
  CalibrateView view;
  JournalWriter* journal = nullptr;                    // may be null
  std::function<void(const std::string&)> log;         // progress lines (the command prints them)
  std::string esc_hint = "Esc quits without saving.";  // what Esc does, in words, on every step
  bool changed = true;  // input or a step since the last frame was drawn (whoever draws clears)
  void say(const std::string& line) const {
    if (log) log(line);
  }
};

class CalibrateScreen : public Screen {
 public:
  explicit CalibrateScreen(CalibrateContext& context) : context_(context) {}
  // On its own, a screen feeds the samples through the shared pen input and handles each
  // event; a flow feeds the input itself and routes event by event, so the events after the
  // one that completed a screen go to the next.
  void onPenSamples(const std::vector<PenSample>& samples) override {
    if (!samples.empty()) context_.changed = true;
    context_.input.feed(samples, [this](const CalibratePenEvent& e) { onPenEvent(e); });
  }
  virtual void onPenEvent(const CalibratePenEvent& e) { (void)e; }
  // Redrawn when the pen moved, a key was pressed or a step was taken.
  bool needsFrame() const override { return context_.changed; }
  void onCommand(Command command, int64_t t_ns) override {
    (void)command;
    (void)t_ns;
  }

 protected:
  CalibrateContext& context_;
};

}  // namespace cb
