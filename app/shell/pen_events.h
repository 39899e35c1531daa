// Pen events, derived once from the calibrated sample stream and routed to the active screen
// (DESIGN.md "The shell"). Contact is the calibration's hysteresis (MappedSample::contact*), the
// one place that decides pen-down. Per sample the events come in one fixed order, as libinput's
// tablet code emits them: proximity in, motion (hover or drag), tip down, side buttons, tip up,
// proximity out.
#pragma once

#include <cstdint>
#include <vector>

#include "calibration/mapped_sample.h"

namespace cb {

struct PenEvent {
  enum class Kind {
    kProximityIn,
    kHover,
    kDown,
    kDrag,
    kUp,
    kButtonDown,
    kButtonUp,
    kProximityOut
  };
  Kind kind;
  int64_t t_ns = 0;
  float x = 0.0f, y = 0.0f;  // screen pixels (filtered, unpredicted), y down
  float pressure = 0.0f;
  uint32_t button = 0;  // kButton*: the PenButton bit (kPenStylus1 lower, kPenStylus2 upper)
};

const char* penEventName(PenEvent::Kind kind);

class PenEventDeriver {
 public:
  // Appends this sample's events to *events.
  void derive(const MappedSample& sample, std::vector<PenEvent>* events);
  bool inProximity() const { return in_proximity_; }
  bool down() const { return down_; }

 private:
  bool in_proximity_ = false;
  bool down_ = false;
  uint32_t buttons_ = 0;  // side buttons held
};

}  // namespace cb
