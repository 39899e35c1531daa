// The evdev pen state machine: kernel input events in, one PenSample per SYN_REPORT frame out.
// Pure (no file descriptors), so it is tested on recorded event streams.
#pragma once

#include <linux/input.h>

#include <cstdint>

#include "drivers/core/pen_sample.h"

namespace cb {

class EvdevPenState {
 public:
  explicit EvdevPenState(const PenDeviceInfo& info) : info_(info) {}
  // Feeds one event; at SYN_REPORT returns true and fills `out` when the frame produced a
  // sample (pen in proximity, or the frame in which it left).
  bool feed(const input_event& ev, PenSample& out);
  // The device vanished: a proximity-out sample if a pen was in proximity.
  bool disconnect(int64_t t_ns, PenSample& out);
  // Sets current values (e.g. from libevdev after opening or a SYN_DROPPED resync).
  void setAbs(uint16_t code, int32_t value);
  void setKey(uint16_t code, bool down);
  bool inProximity() const { return last_.in_proximity; }

 private:
  PenDeviceInfo info_;
  int32_t x_ = 0, y_ = 0, pressure_ = 0, tilt_x_ = 0, tilt_y_ = 0, distance_ = 0, misc_ = 0;
  uint32_t serial_ = 0;
  bool touch_ = false, stylus_ = false, stylus2_ = false, tool_rubber_ = false;
  uint32_t pen_tools_ = 0;  // BTN_TOOL_PEN/PENCIL/BRUSH/AIRBRUSH bits
  PenSample last_{};
};

}  // namespace cb
