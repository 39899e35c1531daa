#include "drivers/keyboard/evdev_key_tracker.h"

namespace cb {

void EvdevKeyTracker::feed(const input_event& event, std::vector<KeyTransition>* out) {
  if (event.type == EV_SYN && event.code == SYN_DROPPED) {
    dropping_ = true;
    needs_resync_ = true;
    return;
  }
  if (dropping_) {  // everything up to and including the next SYN_REPORT is incomplete
    if (event.type == EV_SYN && event.code == SYN_REPORT) dropping_ = false;
    return;
  }
  if (event.type != EV_KEY || event.code >= KEY_CNT || event.value == 2) return;  // 2: repeat
  const bool down = event.value != 0;
  if (down_[event.code] == down) return;  // already known (e.g. delivered by a resync)
  down_[event.code] = down;
  out->push_back({int(event.code), down});
}

void EvdevKeyTracker::resync(const uint8_t* key_bits, size_t bytes,
                             std::vector<KeyTransition>* out) {
  needs_resync_ = false;
  const auto now_down = [&](size_t code) {
    return code / 8 < bytes && ((key_bits[code / 8] >> (code % 8)) & 1u) != 0;
  };
  for (size_t code = 0; code < KEY_CNT; ++code)
    if (down_[code] && !now_down(code)) {
      down_[code] = false;
      out->push_back({int(code), false});
    }
  for (size_t code = 0; code < KEY_CNT; ++code)
    if (!down_[code] && now_down(code)) {
      down_[code] = true;
      out->push_back({int(code), true});
    }
}

}  // namespace cb
