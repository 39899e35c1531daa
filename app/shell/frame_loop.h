// The shell's one frame loop: display events → keymap → commands for the active screen, pen
// samples → the screen, the screen's frame → present, frame timing. Every interactive command
// runs its screens through this loop.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "app/render/gl/display.h"
#include "app/shell/screen.h"

namespace cb {

class Clock;
class EvdevKeyboards;
class PenSource;

struct FrameLoopOptions {
  long max_frames = 0;                      // stop after this many presented frames (0: no limit)
  double max_seconds = 0.0;                 // stop after this long (0: no limit)
  std::vector<DisplayEvent> initial_keys;   // pressed before the first frame (scripted runs)
  const std::atomic<bool>* stop = nullptr;  // set by signal handlers
  std::function<void(const FrameContext&)> after_draw;  // tests: after drawing, before present
  // Every iteration, drawn or idle (the service watchdog pings from here: a hung loop stops
  // them), with whether a frame was presented.
  std::function<void(bool presented)> each_iteration;
  // The clock of FrameContext::now_ns / since_last_s and of command times, which screens' timers
  // read (tests drive a ManualClock); null: the monotonic clock. max_seconds and the frame
  // timings passed to presented() stay on the monotonic clock.
  const Clock* clock = nullptr;
  // A drawn iteration that took at least this long (monotonic seconds) is logged on stderr with
  // its phases (input and pen, update, draw, present); 0: never.
  double slow_iteration_s = 2.0;
};

struct FrameLoopResult {
  long frames = 0;
  double seconds = 0.0;
  std::string quit_reason;  // "Esc", "q", "window closed", "frame limit", "signal", or the screen's
  std::vector<std::string> commands;  // every command routed, by name, in order (tests, logs)
  long abandoned_frames = 0;  // drawn in part and given up for waiting input (not presented)
};

class FrameLoop {
 public:
  // Where the display has no keys of its own (KMS), the keyboards are opened here through evdev
  // (drivers/keyboard) and read with the display's events.
  FrameLoop(Display& display, PenSource* pen);
  ~FrameLoop();
  // Runs `screen` until a quit; false with *error when drawing or presenting fails.
  bool run(Screen& screen, const FrameLoopOptions& options, FrameLoopResult* result,
           std::string* error);

 private:
  // The display's events and, on KMS, the evdev keyboards' presses, appended to `pending`.
  void pollInput(std::vector<DisplayEvent>* pending);

  Display& display_;
  PenSource* pen_;
  std::unique_ptr<EvdevKeyboards> keyboards_;  // KMS only: Esc and the mode keys on the console
};

}  // namespace cb
