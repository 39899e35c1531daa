#include "app/shell/calibrate/calibrate_targets_screen.h"

#include <cstdio>

namespace cb {

void CalibrateTargetsScreen::restart() {
  taps_.clear();
  collector_ = TapCollector();
  problem_.clear();
}

void CalibrateTargetsScreen::onPenEvent(const CalibratePenEvent& e) {
  if (taps_.size() >= targets_.size()) return;
  const std::optional<glm::dvec2> tap = collectTap(collector_, e);
  if (!tap) {
    if (e.event.kind == PenEvent::Kind::kUp && !collector_.lastRejection().empty()) {
      problem_ = collector_.lastRejection();
      context_.say("target " + std::to_string(taps_.size()) + ": " + problem_);
    }
    return;
  }
  problem_.clear();
  taps_.push_back({targets_[taps_.size()], *tap});
  char line[96];
  std::snprintf(line, sizeof line, "target %zu: tap at (%.2f, %.2f) mm", taps_.size() - 1, tap->x,
                tap->y);
  context_.say(line);
  if (taps_.size() == targets_.size()) on_done_(taps_);
}

bool CalibrateTargetsScreen::draw(FrameContext& frame, std::string* error) {
  CalibrateView& v = context_.view;
  const int w = frame.width, h = frame.height;
  v.begin(frame.display.framebuffer(), w, h, {0.08f, 0.09f, 0.11f});
  const size_t n = targets_.size(), k = std::min(taps_.size(), n - 1);
  v.rect(0, 0, w * double(taps_.size()) / double(n), 6, {0.3f, 0.7f, 0.3f});
  for (size_t i = 0; i < taps_.size(); ++i) v.crosshair(targets_[i], 8, {0.3f, 0.6f, 0.3f});
  const glm::dvec2 t = targets_[k];
  v.crosshair(t, 30, {1.0f, 1.0f, 1.0f});
  // The centre dot turns dark while the pen is down.
  v.rect(t.x - 3, t.y - 3, 7, 7,
         collector_.inContact() ? glm::vec3(0.2f, 0.3f, 0.2f) : glm::vec3(1.0f, 0.3f, 0.2f));
  if (context_.input.inRange()) v.cursor(context_.input.cursor());
  const float size = v.bodySize();
  char line[96];
  std::snprintf(line, sizeof line, "Tap the centre of the cross with the pen (%zu of %zu)", k + 1,
                n);
  v.label(float(w) * 0.5f, float(h) * 0.5f + size * 2.5f, line);
  v.label(float(w) * 0.5f, float(h) * 0.5f + size * 4.0f,
          "Touch with the tip and lift without sliding. " + context_.esc_hint, size * 0.8f,
          0xd0d8e0ffu);
  if (!problem_.empty())
    v.label(float(w) * 0.5f, float(h) * 0.5f + size * 5.3f, "Not counted: " + problem_, size * 0.8f,
            0xffb060ffu);
  return v.finish(error);
}

}  // namespace cb
