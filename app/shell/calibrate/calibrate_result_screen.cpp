#include "app/shell/calibrate/calibrate_result_screen.h"

#include <algorithm>
#include <cstdio>

#include "calibration/point_fit.h"

namespace cb {

CalibrateResultScreen::CalibrateResultScreen(CalibrateContext& context, CalibrationFit fit,
                                             std::vector<Tap> taps,
                                             const glm::dmat3& area_to_screen, bool auto_accept,
                                             std::function<void(Choice)> on_done)
    : CalibrateScreen(context),
      fit_(std::move(fit)),
      taps_(std::move(taps)),
      area_to_screen_(area_to_screen),
      auto_accept_(auto_accept),
      on_done_(std::move(on_done)) {}

namespace {
// 180×100 px, lower on a short screen (at most a fifth of its height) so that a box stays clear
// of the middle row's residual labels (16 px below the crosses at half height) and of the
// bottom row's crosses (at 0.9 of the height): at 640×360 a 100 px box overlapped the labels.
CalibrateBox choiceBox(double centre_x, int height) {
  const double h = std::min(100.0, 0.2 * height);
  return {centre_x - 90, height * 0.7 - h / 2, 180, h};
}
}  // namespace

CalibrateBox CalibrateResultScreen::acceptBox(int width, int height) {
  return choiceBox(width * 0.3, height);
}
CalibrateBox CalibrateResultScreen::redoBox(int width, int height) {
  return choiceBox(width * 0.7, height);
}

void CalibrateResultScreen::choose(Choice choice) {
  if (chosen_) return;
  chosen_ = true;
  on_done_(choice);
}

void CalibrateResultScreen::onPenEvent(const CalibratePenEvent& e) {
  if (e.event.kind != PenEvent::Kind::kUp) return;
  const glm::dvec2 at(e.event.x, e.event.y);
  if (acceptBox(context_.width, context_.height).contains(at)) choose(Choice::kAccept);
  if (redoBox(context_.width, context_.height).contains(at)) choose(Choice::kRedo);
}

void CalibrateResultScreen::onCommand(Command command, int64_t t_ns) {
  (void)t_ns;
  if (command == Command::kSpace) choose(Choice::kAccept);
}

std::string CalibrateResultScreen::update(const FrameContext& frame) {
  (void)frame;
  if (auto_accept_ && shown_) choose(Choice::kAccept);
  return "";
}

void CalibrateResultScreen::presented(const FrameContext& frame, double frame_ms) {
  (void)frame;
  (void)frame_ms;
  shown_ = true;
}

bool CalibrateResultScreen::draw(FrameContext& frame, std::string* error) {
  CalibrateView& v = context_.view;
  const int w = frame.width, h = frame.height;
  v.begin(frame.display.framebuffer(), w, h, {0.08f, 0.09f, 0.11f});
  const float size = v.bodySize();
  for (size_t i = 0; i < taps_.size() && i < fit_.fit.residuals.size(); ++i) {
    const glm::dvec2 mapped =
        applyTransform(fit_.profile.correction, applyTransform(area_to_screen_, taps_[i].pen_mm));
    v.crosshair(taps_[i].target_px, 12, {0.8f, 0.8f, 0.8f});
    v.rect(mapped.x - 3, mapped.y - 3, 7, 7, {1.0f, 0.3f, 0.2f});
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f px", fit_.fit.residuals[i]);
    v.label(float(taps_[i].target_px.x) + 16.0f, float(taps_[i].target_px.y) + 16.0f, buf,
            size * 0.8f, 0xffffffffu, false);
  }
  // What the numbers mean and what to do next, between the top and middle rows of targets.
  const bool good = fit_.fit.max_residual <= 3.0;
  char buf[160];
  std::snprintf(buf, sizeof buf, "Largest error %.2f px, rms %.2f px (%s fit, %zu points)",
                fit_.fit.max_residual, fit_.fit.rms, pointFitKindName(fit_.profile.fit_kind),
                taps_.size());
  v.label(float(w) * 0.5f, float(h) * 0.3f - 1.5f * size, buf, size * 1.2f, 0xffff99ffu);
  v.label(float(w) * 0.5f, float(h) * 0.3f - 0.2f * size,
          good ? "Good: the pen lands within a few pixels of the crosses."
               : "Some taps are far off: check the crosses (red squares) and redo if one slipped.",
          size * 0.8f, good ? 0xa0e0a0ffu : 0xffb060ffu);
  const CalibrateBox accept = acceptBox(w, h), redo = redoBox(w, h);
  v.box(accept, {0.2f, 0.65f, 0.25f});
  v.box(redo, {0.9f, 0.5f, 0.1f});
  v.label(float(accept.x + accept.w * 0.5), float(accept.y + accept.h + 0.4 * size),
          "Accept and save (Space)");
  v.label(float(redo.x + redo.w * 0.5), float(redo.y + redo.h + 0.4 * size), "Redo the taps");
  // The third line of the block above the middle row (just above the boxes it crossed the middle
  // cross at 640×360).
  v.label(float(w) * 0.5f, float(h) * 0.3f + 1.0f * size,
          "Tap a box with the pen. " + context_.esc_hint, size * 0.8f, 0xd0d8e0ffu);
  if (context_.input.inRange()) v.cursor(context_.input.cursor());
  return v.finish(error);
}

}  // namespace cb
