// The keys of one evdev keyboard as the kernel reports them, kept in step across SYN_DROPPED
// (the kernel's client buffer overflowed, e.g. keys typed while a frame took seconds): the
// events up to the next SYN_REPORT are discarded, then the device's real key state (EVIOCGKEY)
// is compared with what was known, and the difference is delivered as key transitions — as
// libevdev does (Documentation/input/event-codes.rst, "SYN_DROPPED"). Without it a modifier
// whose release was dropped stays held (Ctrl stuck: every later key a Ctrl combination).
// Pure: the caller reads the device and makes the ioctl.
#pragma once

#include <linux/input.h>

#include <bitset>
#include <cstdint>
#include <vector>

namespace cb {

struct KeyTransition {
  int code = 0;  // KEY_*
  bool down = false;
};

class EvdevKeyTracker {
 public:
  // One event as read from the device; appends the key presses and releases to deliver
  // (auto-repeats, repeats of a known state and events cut off by a SYN_DROPPED are not).
  void feed(const input_event& event, std::vector<KeyTransition>* out);
  // A SYN_DROPPED was read: the caller reads EVIOCGKEY and calls resync() (after draining what
  // the device had, so the state read is the newest).
  bool needsResync() const { return needs_resync_; }
  // `key_bits`: EVIOCGKEY's bitmask (bit KEY_x of byte KEY_x / 8). Appends releases of keys
  // now up, then presses of keys now down, each against what the tracker knew.
  void resync(const uint8_t* key_bits, size_t bytes, std::vector<KeyTransition>* out);
  bool isDown(int code) const { return code >= 0 && code < KEY_CNT && down_[size_t(code)]; }

 private:
  std::bitset<KEY_CNT> down_;
  bool dropping_ = false;  // between SYN_DROPPED and the next SYN_REPORT
  bool needs_resync_ = false;
};

}  // namespace cb
