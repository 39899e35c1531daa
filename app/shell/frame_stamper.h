// The frame loop's per-frame timing record (drivers/core/journal_frame.h): when the frame began,
// which pen samples it is the first to show, when it was ready (drawn and finished) and when it
// reached the screen — on KMS the page-flip event's vblank time, on X11 when swap + glFinish
// returned (no Present completion events are read), offscreen when glFinish returned — its CPU
// time on the loop thread, and whether it missed a refresh. Samples stamped on another clock (a
// recording replayed at its recorded times) are counted without a time. Samples taken for a frame
// that was not presented (abandoned, idle) count for the next presented one.
#pragma once

#include <cstdint>
#include <vector>

#include "drivers/core/journal_frame.h"
#include "drivers/core/pen_sample.h"

namespace cb {

class Display;

class FrameStamper {
 public:
  explicit FrameStamper(const Display& display);
  // The loop begins an iteration (monotonic ns).
  void begin(int64_t now_ns);
  // Pen samples handed to the screen for the frame being made (also the late-latched ones).
  void samplesTaken(const std::vector<PenSample>& samples);
  // The frame is drawn and finished on the GPU (call after glFinish, before present).
  void ready(int64_t now_ns);
  // After present: the record, its times moved by `clock_offset_ns` onto the loop's clock (the
  // pen samples' time line). `after_idle`: the loop slept since the last present, so a long
  // interval is no missed refresh.
  FrameRecord presented(bool after_idle, bool lift, int64_t clock_offset_ns);

 private:
  const Display& display_;
  PresentSource source_;
  uint32_t refresh_us_;
  bool nominal_refresh_;
  uint32_t frames_ = 0;
  int64_t begin_ns_ = 0, ready_ns_ = 0, cpu_begin_ns_ = 0, cpu_ready_ns_ = 0;
  int64_t oldest_ns_ = 0, newest_ns_ = 0;
  uint32_t new_samples_ = 0;
  int64_t last_present_ns_ = 0;
  uint32_t last_sequence_ = 0;
};

}  // namespace cb
