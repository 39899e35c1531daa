// Keyboard on the KMS platform, where no window system delivers keys: every /dev/input/event*
// that has an Esc key is read non-blocking through the kernel's evdev interface. Enough for
// "Esc quits"; the pen has its own drivers in drivers/evdev.
#pragma once

#include <vector>

#include "app/render/gl/display.h"

namespace cb {

class EvdevKeyboards {
 public:
  EvdevKeyboards();  // opens what it can; no keyboard is not an error
  ~EvdevKeyboards();
  EvdevKeyboards(const EvdevKeyboards&) = delete;
  EvdevKeyboards& operator=(const EvdevKeyboards&) = delete;

  size_t count() const { return fds_.size(); }
  // Key presses since the last call (never blocks).
  std::vector<DisplayEvent> poll();

 private:
  std::vector<int> fds_;
};

}  // namespace cb
