// A screen of the shell: what the frame loop (frame_loop.h) shows and routes input to — the
// painter, and later calibration, the study runner and the exhibition's attract screen. The loop
// owns the display, pen and key input, timing and presenting; a screen handles pen samples,
// commands and pointer events, and draws one frame into the framebuffer it is given
// (kmscube's shape: one loop, one draw per scene).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "app/render/gl/display.h"
#include "app/shell/command.h"
#include "drivers/core/journal_frame.h"
#include "drivers/core/pen_sample.h"

namespace cb {

struct FrameContext {
  Display& display;
  int width = 0, height = 0;
  long frame = 0;           // frames presented before this one
  int64_t now_ns = 0;       // monotonic time of this frame
  double since_last_s = 0;  // seconds since the previous frame was presented
  // Whether input waits to be taken (the pen's reader thread has news, PenSource::inputWaiting):
  // a screen drawing a long frame in slices asks between them and may give the frame up, so a
  // visitor's pen is taken at once rather than after the frame. Null: nothing can tell.
  std::function<bool()> input_waiting = nullptr;
  // Set by draw() when it gave the frame up for waiting input: the loop does not present it (the
  // last frame stays on the screen) and goes round again at once, taking the input.
  bool abandoned = false;
  // Late latching: hands the screen (onPenSamples) the pen samples that arrived since the frame
  // began, so the ink drawn next shows them. A screen calls it after its slow work (the scene),
  // right before drawing the ink. Null: no pen.
  std::function<void()> latch_pen = nullptr;
  // Set by draw() when the frame shows a lifted stroke's cloud (journalled: the pen-up wait, not
  // the ink's).
  bool shows_lift = false;
  // In presented(): this frame's timing (present time, newest sample shown, CPU time, missed
  // refresh), for the screen to journal. Null before present.
  const FrameRecord* record = nullptr;
};

class Screen {
 public:
  virtual ~Screen() = default;
  virtual const char* name() const = 0;
  // Pen samples polled since the last frame (raw, as the driver gave them), with the source's
  // connection state; called once per frame, also with no samples.
  virtual void onPenSamples(const std::vector<PenSample>& samples) { (void)samples; }
  virtual void onCommand(Command command, int64_t t_ns) = 0;
  // A key before the keymap sees it; true when the screen took it (the keymap then does not).
  // The kiosk's operator combination and PIN digits come through here.
  virtual bool onKey(const DisplayEvent& event, int64_t t_ns) {
    (void)event;
    (void)t_ns;
    return false;
  }
  virtual void onPointer(const DisplayEvent& event) { (void)event; }
  virtual void onResize(int width, int height) {
    (void)width;
    (void)height;
  }
  // Timers; a non-empty result ends the loop with that reason.
  virtual std::string update(const FrameContext& frame) {
    (void)frame;
    return "";
  }
  // False when the last frame still shows everything (the loop sleeps instead of drawing).
  virtual bool needsFrame() const { return true; }
  // Draws one frame into frame.display.framebuffer(). False with *error stops the loop.
  virtual bool draw(FrameContext& frame, std::string* error) = 0;
  // After present(): how long the frame took, present to present.
  virtual void presented(const FrameContext& frame, double frame_ms) {
    (void)frame;
    (void)frame_ms;
  }
  // Whether Command::kQuit ends the loop (a kiosk's visitor screen says no).
  virtual bool allowsQuit() const { return true; }
};

}  // namespace cb
