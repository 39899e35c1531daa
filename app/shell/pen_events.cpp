#include "app/shell/pen_events.h"

#include "drivers/core/pen_sample.h"

namespace cb {

const char* penEventName(PenEvent::Kind kind) {
  switch (kind) {
    case PenEvent::Kind::kProximityIn:
      return "proximity-in";
    case PenEvent::Kind::kHover:
      return "hover";
    case PenEvent::Kind::kDown:
      return "down";
    case PenEvent::Kind::kDrag:
      return "drag";
    case PenEvent::Kind::kUp:
      return "up";
    case PenEvent::Kind::kButtonDown:
      return "button-down";
    case PenEvent::Kind::kButtonUp:
      return "button-up";
    case PenEvent::Kind::kProximityOut:
      return "proximity-out";
  }
  return "?";
}

void PenEventDeriver::derive(const MappedSample& s, std::vector<PenEvent>* events) {
  const auto emit = [&](PenEvent::Kind kind, uint32_t button = 0) {
    events->push_back(PenEvent{kind, s.t_ns, float(s.x_px), float(s.y_px), s.pressure, button});
  };
  const bool near = s.in_proximity || s.contact;
  if (near && !in_proximity_) {
    in_proximity_ = true;
    emit(PenEvent::Kind::kProximityIn);
  }
  if (near) emit(down_ && s.contact ? PenEvent::Kind::kDrag : PenEvent::Kind::kHover);
  if (s.contact && !down_) {
    down_ = true;
    emit(PenEvent::Kind::kDown);
  }
  const uint32_t side = near ? (s.raw.buttons & (kPenStylus1 | kPenStylus2)) : 0u;
  for (uint32_t bit : {uint32_t(kPenStylus1), uint32_t(kPenStylus2)}) {
    if ((side & bit) && !(buttons_ & bit)) emit(PenEvent::Kind::kButtonDown, bit);
    if (!(side & bit) && (buttons_ & bit)) emit(PenEvent::Kind::kButtonUp, bit);
  }
  buttons_ = side;
  if (!s.contact && down_) {
    down_ = false;
    emit(PenEvent::Kind::kUp);
  }
  if (!near && in_proximity_) {
    in_proximity_ = false;
    emit(PenEvent::Kind::kProximityOut);
  }
}

}  // namespace cb
