#include "app/shell/painter/paint_loop.h"

#include <algorithm>

#include "app/shell/frame_loop.h"
#include "app/shell/painter/paint_screen.h"

namespace cb {

double PaintLoopSummary::median_pen_up_to_lit_ms() const {
  if (pen_up_to_lit_ms.empty()) return 0.0;
  std::vector<double> values = pen_up_to_lit_ms;
  std::nth_element(values.begin(), values.begin() + long(values.size() / 2), values.end());
  return values[values.size() / 2];
}

PaintLoop::PaintLoop(Display& display, VolumeRenderer& renderer, const Volume& volume,
                     const Light& light, const PaintLoopOptions& options)
    : display_(display),
      screen_(std::make_unique<PaintScreen>(display, renderer, volume, light, options)),
      options_(options) {}

PaintLoop::~PaintLoop() = default;

void PaintLoop::attachPen(PenSource* pen, PaintSession* session) {
  pen_ = pen;
  screen_->attachPen(pen, session);
}

bool PaintLoop::run(const std::atomic<bool>* stop, PaintLoopSummary* summary, std::string* error,
                    Screen* front) {
  *summary = PaintLoopSummary{};
  FrameLoopOptions loop_options;
  loop_options.max_frames = options_.max_frames;
  loop_options.max_seconds = options_.max_seconds;
  loop_options.initial_keys = options_.initial_keys;
  loop_options.stop = stop;
  loop_options.each_iteration = options_.each_iteration;
  loop_options.clock = options_.clock;
  FrameLoop loop(display_, pen_);
  FrameLoopResult result;
  if (!loop.run(front ? *front : *screen_, loop_options, &result, error)) return false;
  routed_ = result.commands;
  screen_->finish(summary);
  summary->frames = result.frames;
  summary->seconds = result.seconds;
  summary->quit_reason = result.quit_reason;
  std::vector<double> present_ms;
  const FrameTimingRing& timings = display_.frameTimings();
  for (size_t i = 0; i < timings.size(); ++i)
    present_ms.push_back(double(timings.at(i).shown_ns - timings.at(i).submit_ns) / 1e6);
  if (!present_ms.empty()) {
    std::nth_element(present_ms.begin(), present_ms.begin() + long(present_ms.size() / 2),
                     present_ms.end());
    summary->median_present_ms = present_ms[present_ms.size() / 2];
  }
  return true;
}

}  // namespace cb
