#include "app/shell/frame_loop.h"

#include <chrono>
#include <cstdio>
#include <thread>

#include "app/render/gl/gl.h"
#include "app/shell/frame_stamper.h"
#include "app/shell/keymap.h"
#include "drivers/core/clock.h"
#include "drivers/core/pen_source.h"
#include "drivers/keyboard/evdev_keyboards.h"

namespace cb {
namespace {

int64_t monotonicNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

int64_t loopNowNs(const Clock* clock) {
  return clock ? clock->nowNs() : monotonicNs();
}

// The display's events to the screen: a key goes to the screen first (onKey), else through the
// keymap to a command. Returns why the loop quits ("window closed", "q", "Esc") or "".
std::string routeEvents(const std::vector<DisplayEvent>& events, Screen& screen, const Clock* clock,
                        FrameLoopResult* result) {
  std::string quit;
  for (const DisplayEvent& event : events) {
    if (!quit.empty()) break;
    switch (event.kind) {
      case DisplayEvent::Kind::Quit:
        quit = "window closed";
        break;
      case DisplayEvent::Kind::KeyDown: {
        if (screen.onKey(event, loopNowNs(clock))) break;
        const std::optional<Command> command = commandForKey(event.keysym, event.modifiers);
        if (!command) break;
        result->commands.push_back(commandName(*command));
        if (*command == Command::kQuit && screen.allowsQuit())
          quit = event.keysym == 'q' || event.keysym == 'Q' ? "q" : "Esc";
        else
          screen.onCommand(*command, loopNowNs(clock));
        break;
      }
      case DisplayEvent::Kind::Resize:
        screen.onResize(event.width, event.height);
        break;
      default:
        screen.onPointer(event);
        break;
    }
  }
  return quit;
}

// Monotonic marks of one drawn iteration: start, pen taken, updated, drawn, presented.
struct IterationMarks {
  int64_t start, pen, update, draw, presented;
};

void logSlowIteration(long frame, const IterationMarks& m) {
  std::fprintf(stderr,
               "cloudbrush: slow loop iteration (frame %ld): %.2f s = input+pen %.2f, update "
               "%.2f, draw %.2f, present %.2f (ended at %.6f s monotonic)\n",
               frame, double(m.presented - m.start) / 1e9, double(m.pen - m.start) / 1e9,
               double(m.update - m.pen) / 1e9, double(m.draw - m.update) / 1e9,
               double(m.presented - m.draw) / 1e9, double(m.presented) / 1e9);
}

static_assert(uint32_t(kKeyShift) == DisplayEvent::kShift &&
                  uint32_t(kKeyCtrl) == DisplayEvent::kCtrl &&
                  uint32_t(kKeyAlt) == DisplayEvent::kAlt,
              "the keyboard's modifier bits are the display's");

}  // namespace

FrameLoop::FrameLoop(Display& display, PenSource* pen) : display_(display), pen_(pen) {
  if (display_.needsEvdevKeyboard()) keyboards_ = std::make_unique<EvdevKeyboards>();
}

FrameLoop::~FrameLoop() = default;

void FrameLoop::pollInput(std::vector<DisplayEvent>* pending) {
  for (const DisplayEvent& event : display_.pollEvents()) pending->push_back(event);
  if (keyboards_)
    for (const KeyPress& key : keyboards_->poll())
      pending->push_back(DisplayEvent::key(key.keysym, key.modifiers));
}

bool FrameLoop::run(Screen& screen, const FrameLoopOptions& options, FrameLoopResult* result,
                    std::string* error) {
  *result = FrameLoopResult{};
  const int64_t start = monotonicNs();
  int64_t last_present = start;
  const auto now_ns = [&]() { return loopNowNs(options.clock); };
  int64_t last_frame_ns = now_ns();
  std::vector<DisplayEvent> pending = options.initial_keys;
  std::vector<PenSample> samples;
  // Phase marks of one iteration (monotonic), for the slow-iteration log line.
  int64_t mark_start = 0, mark_pen = 0, mark_update = 0, mark_draw = 0;
  FrameStamper stamper(display_);
  bool idled = false;  // the loop slept (nothing to draw) since the last present
  while (true) {
    mark_start = monotonicNs();
    stamper.begin(mark_start);
    pollInput(&pending);
    std::string quit = routeEvents(pending, screen, options.clock, result);
    pending.clear();
    if (quit.empty() && options.stop && options.stop->load()) quit = "signal";
    if (quit.empty() && options.max_frames > 0 && result->frames >= options.max_frames)
      quit = "frame limit";
    if (quit.empty() && options.max_seconds > 0.0 &&
        double(monotonicNs() - start) / 1e9 >= options.max_seconds)
      quit = "time limit";
    const int64_t now = now_ns();
    FrameContext frame{display_,
                       display_.width(),
                       display_.height(),
                       result->frames,
                       now,
                       double(now - last_frame_ns) / 1e9};
    if (pen_) frame.input_waiting = [this] { return pen_->inputWaiting(); };
    if (quit.empty() && pen_) {
      samples.clear();
      pen_->poll(0, samples);
      stamper.samplesTaken(samples);
      screen.onPenSamples(samples);
      frame.latch_pen = [&] {
        samples.clear();
        pen_->poll(0, samples);
        if (samples.empty()) return;
        stamper.samplesTaken(samples);
        screen.onPenSamples(samples);
      };
    }
    mark_pen = monotonicNs();
    if (quit.empty()) quit = screen.update(frame);
    mark_update = monotonicNs();
    if (!quit.empty()) {
      result->quit_reason = quit;
      break;
    }
    if (!screen.needsFrame()) {
      // Nothing changed: wait a tick. A scripted run (max_frames) counts the tick as a frame,
      // so `--frames N` ends even on a still scene.
      std::this_thread::sleep_for(std::chrono::milliseconds(15));
      if (options.max_frames > 0) ++result->frames;
      idled = true;
      if (options.each_iteration) options.each_iteration(false);
      continue;
    }
    if (!screen.draw(frame, error)) return false;
    if (frame.abandoned) {
      // Given up for waiting input: not presented; the next iteration takes the input at once.
      ++result->abandoned_frames;
      if (options.each_iteration) options.each_iteration(false);
      continue;
    }
    if (options.after_draw) options.after_draw(frame);
    glFinish();  // the frame is ready: drawn, not only queued (sample -> frame-ready)
    mark_draw = monotonicNs();
    stamper.ready(mark_draw);
    if (!display_.present(error)) return false;
    const int64_t presented = monotonicNs();
    const FrameRecord record = stamper.presented(
        idled, frame.shows_lift, options.clock ? options.clock->nowNs() - monotonicNs() : 0);
    idled = false;
    frame.record = &record;
    if (options.slow_iteration_s > 0.0 &&
        double(presented - mark_start) / 1e9 >= options.slow_iteration_s)
      logSlowIteration(result->frames, {mark_start, mark_pen, mark_update, mark_draw, presented});
    screen.presented(frame, double(presented - last_present) / 1e6);
    last_present = presented;
    last_frame_ns = now;
    ++result->frames;
    if (options.each_iteration) options.each_iteration(true);
  }
  result->seconds = double(monotonicNs() - start) / 1e9;
  return true;
}

}  // namespace cb
