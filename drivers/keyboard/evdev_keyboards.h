// Keyboards read without a window system (the KMS platform, where none delivers keys): every
// /dev/input/event* that has an Esc key is read non-blocking through the kernel's evdev
// interface, and key codes become keysyms through an XKB keymap (libxkbcommon, the layout from
// the XKB_DEFAULT_* variables or the system default), so Ctrl+Z is Ctrl+Z on any layout. Where no
// keymap compiles (no xkb-data, as in a minimal initramfs) a built-in US table is used and said
// so on stderr. Events the kernel drops when its buffer overflows (keys typed during a long
// frame) are recovered by reading the key state again (evdev_key_tracker.h). The pen has its own
// backends in drivers/evdev; the shell's frame loop polls this where the display asks for it
// (Display::needsEvdevKeyboard) and turns presses into DisplayEvents.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "drivers/keyboard/evdev_key_tracker.h"

struct xkb_context;
struct xkb_keymap;
struct xkb_state;

namespace cb {

// One key press: `keysym` an XKB keysym (<xkbcommon/xkbcommon-keysyms.h>), `modifiers` the
// KeyModifier bits held (the same bits as DisplayEvent::Modifier).
enum KeyModifier : uint32_t { kKeyShift = 1, kKeyCtrl = 2, kKeyAlt = 4 };
struct KeyPress {
  uint32_t keysym = 0;
  uint32_t modifiers = 0;
};

class EvdevKeyboards {
 public:
  EvdevKeyboards();  // opens what it can; no keyboard is not an error
  ~EvdevKeyboards();
  EvdevKeyboards(const EvdevKeyboards&) = delete;
  EvdevKeyboards& operator=(const EvdevKeyboards&) = delete;

  size_t count() const { return fds_.size(); }
  // Key presses since the last call (never blocks).
  std::vector<KeyPress> poll();

  // The keysym and modifiers of a Linux key code (KEY_*) press given the modifier keys held
  // (exposed for tests of the built-in table).
  static uint32_t fallbackKeysym(int code, bool shift);
  // Times the kernel dropped key events and the key state was read again.
  long resyncs() const { return resyncs_; }

 private:
  std::vector<int> fds_;
  std::vector<EvdevKeyTracker> trackers_;  // one per fd: held keys, SYN_DROPPED resync
  xkb_context* context_ = nullptr;
  xkb_keymap* keymap_ = nullptr;
  xkb_state* state_ = nullptr;
  bool shift_ = false, ctrl_ = false, alt_ = false;  // for the built-in table
  long resyncs_ = 0;
};

}  // namespace cb
