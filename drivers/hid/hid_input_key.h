// One evdev key fed by several HID usages, as hid-input feeds it (drivers/hid/hid-input.c,
// hidinput_hid_event): each usage sends its value only when it differs from the value that usage
// had in the previous report, so the key follows whichever usage changed last (in the order the
// report carries them). Tablet Pick and Secondary Barrel Switch both feed BTN_STYLUS2; Touch and
// Secondary Tip Switch feed BTN_TOUCH next to Tip Switch. With one usage this is its level.
#pragma once

#include <cstddef>

namespace cb::hid {

template <size_t N>
class HidInputKey {
 public:
  // `values[i]` is usage i's value in this report, `present[i]` whether the descriptor has it;
  // usages in report order. Returns true when a usage sent its value (down() is the last one).
  bool update(const bool (&present)[N], const bool (&values)[N]) {
    bool sent = false;
    for (size_t i = 0; i < N; ++i) {
      if (!present[i] || values[i] == last_[i]) continue;
      last_[i] = values[i];
      down_ = values[i];
      sent = true;
    }
    return sent;
  }
  bool down() const { return down_; }
  void reset() { *this = HidInputKey{}; }

 private:
  bool last_[N] = {};
  bool down_ = false;
};

}  // namespace cb::hid
