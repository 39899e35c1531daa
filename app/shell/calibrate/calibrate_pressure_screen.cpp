#include "app/shell/calibrate/calibrate_pressure_screen.h"

#include <algorithm>

namespace cb {

void CalibratePressureScreen::onPenEvent(const CalibratePenEvent& e) {
  if (collector_.step() == PressureRangeCollector::Step::kDone) return;
  const PressureRangeCollector::Step before = collector_.step();
  switch (e.event.kind) {
    case PenEvent::Kind::kDown:
    case PenEvent::Kind::kDrag:
      collector_.feed(true, e.sample.pressure_corrected);
      return;
    case PenEvent::Kind::kUp:
      collector_.feed(false, 0.0f);
      break;
    default:
      return;
  }
  if (collector_.step() == before) return;
  if (collector_.step() == PressureRangeCollector::Step::kFirm) {
    problem_.clear();
    context_.say("now press firmly and hold (0.5 s), then lift");
    return;
  }
  const PressureRangeFit fit = collector_.result();
  if (!fit.range) {
    problem_ = fit.error;
    context_.say(fit.error + "; again: press lightly and hold, then lift");
    collector_.restart();
    return;
  }
  on_done_(fit);
}

bool CalibratePressureScreen::draw(FrameContext& frame, std::string* error) {
  CalibrateView& v = context_.view;
  const int w = frame.width, h = frame.height;
  v.begin(frame.display.framebuffer(), w, h, {0.08f, 0.09f, 0.11f});
  const bool light = collector_.step() == PressureRangeCollector::Step::kLight;
  v.rect(w * 0.3, h * 0.3, w * 0.4, h * 0.4,
         light ? glm::vec3(0.6f, 0.75f, 0.95f) : glm::vec3(0.1f, 0.2f, 0.6f));
  const double held = std::min(1.0, double(collector_.held()) / double(collector_.holdSamples()));
  v.rect(w * 0.3, h * 0.75, w * 0.4, 12, {0.2f, 0.22f, 0.25f});  // the bar's track
  v.rect(w * 0.3, h * 0.75, w * 0.4 * held, 12, {0.3f, 0.8f, 0.3f});
  if (context_.input.inRange()) v.cursor(context_.input.cursor());
  v.say({light ? "Step 1 of 2: press lightly, as gently as you would paint"
               : "Step 2 of 2: now press firmly",
         "Hold the pen still on the tablet until the green bar is full, then lift it.",
         context_.esc_hint},
        0.08f);
  if (!problem_.empty()) v.label(float(w) * 0.5f, float(h) * 0.82f, problem_, 0.0f, 0xffb060ffu);
  return v.finish(error);
}

}  // namespace cb
