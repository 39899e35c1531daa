#include "app/cli/paint_loop.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>
#include <vector>

namespace cb {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

PaintLoop::PaintLoop(Display& display, VolumeRenderer& renderer, const Volume& volume,
                     const Light& light, const PaintLoopOptions& options)
    : display_(display),
      renderer_(renderer),
      volume_(volume),
      light_(light),
      options_(options),
      orbiting_(options.orbit_degrees_per_second != 0.0f) {}

std::string PaintLoop::handleEvents() {
  for (const DisplayEvent& event : display_.pollEvents()) {
    if (event.kind == DisplayEvent::Kind::Quit) return "window closed";
    if (event.isQuitRequest()) return event.key == DisplayEvent::Key::Q ? "q" : "Esc";
    if (event.kind == DisplayEvent::Kind::KeyDown && event.key == DisplayEvent::Key::Space) {
      orbiting_ = !orbiting_;
      refined_ = false;
    }
    if (event.kind == DisplayEvent::Kind::Resize) refined_ = false;
  }
  return "";
}

bool PaintLoop::run(const std::atomic<bool>* stop, PaintLoopSummary* summary, std::string* error) {
  *summary = PaintLoopSummary{};
  const auto start = std::chrono::steady_clock::now();
  auto last_present = start;
  std::vector<double> moving_frame_ms;
  float scale = std::clamp(options_.moving_scale, options_.min_moving_scale, 1.0f);
  RenderOptions render_options;
  while (true) {
    std::string quit = handleEvents();
    if (quit.empty() && stop && stop->load()) quit = "signal";
    if (quit.empty() && options_.max_frames > 0 && summary->frames >= options_.max_frames)
      quit = "frame limit";
    if (!quit.empty()) {
      summary->quit_reason = quit;
      break;
    }
    renderer_.sync(volume_, light_);  // uploads only what changed (nothing, until painting)
    const bool moving = orbiting_;
    if (!moving && refined_) {
      // Still and already sharp: nothing to draw until something changes.
      std::this_thread::sleep_for(std::chrono::milliseconds(15));
      continue;
    }
    const auto now = std::chrono::steady_clock::now();
    if (moving)
      orbit_degrees_ += options_.orbit_degrees_per_second *
                        float(std::chrono::duration<double>(now - last_present).count());
    const Camera camera = Camera::reference().orbited(orbit_degrees_);
    // Quantised to 1/20 so the renderer's reduced-size target is not reallocated every frame.
    render_options.scale =
        moving ? std::max(options_.min_moving_scale, std::round(scale * 20.0f) / 20.0f) : 1.0f;
    render_options.collect_stats = !moving && options_.print_stats;
    glBindFramebuffer(GL_FRAMEBUFFER, display_.framebuffer());
    renderer_.render(camera, display_.width(), display_.height(), display_.framebuffer(),
                     render_options);
    if (!display_.present(error)) return false;
    const auto presented = std::chrono::steady_clock::now();
    const double frame_ms =
        std::chrono::duration<double, std::milli>(presented - last_present).count();
    last_present = presented;
    ++summary->frames;
    if (moving && summary->frames > 1) {
      moving_frame_ms.push_back(frame_ms);
      // Keep the orbit fluid: shrink the resolution when a frame is over budget, grow it back
      // when there is room (≥ 20 fps is the target, issue 2).
      if (frame_ms > options_.target_frame_ms)
        scale = std::max(options_.min_moving_scale, scale * 0.9f);
      else if (frame_ms < 0.7 * options_.target_frame_ms)
        scale = std::min(1.0f, scale * 1.05f);
    }
    if (!moving) {
      refined_ = true;
      ++summary->refined_frames;
      if (options_.print_stats) std::printf("%s\n", renderer_.lastStats().summary().c_str());
    }
  }
  summary->seconds = secondsSince(start);
  summary->final_moving_scale = scale;
  if (!moving_frame_ms.empty()) {
    std::nth_element(moving_frame_ms.begin(),
                     moving_frame_ms.begin() + long(moving_frame_ms.size() / 2),
                     moving_frame_ms.end());
    summary->median_frame_ms = moving_frame_ms[moving_frame_ms.size() / 2];
  }
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
