#include "drivers/keyboard/evdev_keyboards.h"

#include <cstdio>
#include <string>

#include <fcntl.h>
#include <linux/input.h>
#include <sys/ioctl.h>
#include <unistd.h>
#include <xkbcommon/xkbcommon.h>

namespace cb {
namespace {

bool hasBit(const unsigned long* bits, int bit) {
  constexpr int kBitsPerLong = int(sizeof(unsigned long) * 8);
  return (bits[bit / kBitsPerLong] >> (bit % kBitsPerLong)) & 1ul;
}

// Evdev key codes are XKB key codes minus 8 (the X11 convention libxkbcommon keeps).
constexpr int kXkbOffset = 8;

}  // namespace

uint32_t EvdevKeyboards::fallbackKeysym(int code, bool shift) {
  static const char kRow1[] = "qwertyuiop", kRow2[] = "asdfghjkl", kRow3[] = "zxcvbnm";
  const auto letter = [&](char c) { return uint32_t(shift ? c - 'a' + 'A' : c); };
  if (code >= KEY_Q && code <= KEY_P) return letter(kRow1[code - KEY_Q]);
  if (code >= KEY_A && code <= KEY_L) return letter(kRow2[code - KEY_A]);
  if (code >= KEY_Z && code <= KEY_M) return letter(kRow3[code - KEY_Z]);
  if (code >= KEY_1 && code <= KEY_9) return uint32_t('1' + (code - KEY_1));
  // F1-F10 are consecutive key codes, F11 and F12 come later; the keysyms F1-F12 are consecutive.
  if (code >= KEY_F1 && code <= KEY_F10) return uint32_t(XKB_KEY_F1 + (code - KEY_F1));
  switch (code) {
    case KEY_F11:
      return XKB_KEY_F11;
    case KEY_F12:
      return XKB_KEY_F12;
    case KEY_PAGEUP:
      return XKB_KEY_Prior;
    case KEY_PAGEDOWN:
      return XKB_KEY_Next;
    case KEY_HOME:
      return XKB_KEY_Home;
    case KEY_END:
      return XKB_KEY_End;
    case KEY_INSERT:
      return XKB_KEY_Insert;
    case KEY_0:
      return '0';
    case KEY_ESC:
      return XKB_KEY_Escape;
    case KEY_SPACE:
      return XKB_KEY_space;
    case KEY_MINUS:
      return shift ? XKB_KEY_underscore : XKB_KEY_minus;
    case KEY_EQUAL:
      return shift ? XKB_KEY_plus : XKB_KEY_equal;
    case KEY_KPMINUS:
      return XKB_KEY_KP_Subtract;
    case KEY_KPPLUS:
      return XKB_KEY_KP_Add;
    case KEY_DELETE:
      return XKB_KEY_Delete;
    case KEY_BACKSPACE:
      return XKB_KEY_BackSpace;
    case KEY_ENTER:
      return XKB_KEY_Return;
    case KEY_TAB:
      return XKB_KEY_Tab;
    case KEY_UP:
      return XKB_KEY_Up;
    case KEY_DOWN:
      return XKB_KEY_Down;
    case KEY_LEFT:
      return XKB_KEY_Left;
    case KEY_RIGHT:
      return XKB_KEY_Right;
    default:
      return XKB_KEY_NoSymbol;
  }
}

EvdevKeyboards::EvdevKeyboards() {
  for (int i = 0; i < 64; ++i) {
    const std::string path = "/dev/input/event" + std::to_string(i);
    const int fd = open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) continue;
    unsigned long keys[(KEY_MAX + 1) / (sizeof(unsigned long) * 8) + 1] = {};
    if (ioctl(fd, EVIOCGBIT(EV_KEY, sizeof(keys)), keys) >= 0 && hasBit(keys, KEY_ESC)) {
      fds_.push_back(fd);
      trackers_.emplace_back();
    } else {
      close(fd);
    }
  }
  if (fds_.empty()) return;
  context_ = xkb_context_new(XKB_CONTEXT_NO_FLAGS);
  if (context_) keymap_ = xkb_keymap_new_from_names(context_, nullptr, XKB_KEYMAP_COMPILE_NO_FLAGS);
  if (keymap_) state_ = xkb_state_new(keymap_);
  if (!state_)
    std::fprintf(stderr,
                 "cloudbrush: keyboard: no XKB keymap compiles here (is xkb-data installed?); "
                 "keys are read as a US layout\n");
}

EvdevKeyboards::~EvdevKeyboards() {
  for (int fd : fds_) close(fd);
  if (state_) xkb_state_unref(state_);
  if (keymap_) xkb_keymap_unref(keymap_);
  if (context_) xkb_context_unref(context_);
}

std::vector<KeyPress> EvdevKeyboards::poll() {
  std::vector<KeyPress> events;
  std::vector<KeyTransition> keys;
  for (size_t k = 0; k < fds_.size(); ++k) {
    EvdevKeyTracker& tracker = trackers_[k];
    keys.clear();
    input_event ev[32];
    ssize_t n;
    while ((n = read(fds_[k], ev, sizeof(ev))) > 0)
      for (size_t i = 0; i < size_t(n) / sizeof(input_event); ++i) tracker.feed(ev[i], &keys);
    if (tracker.needsResync()) {
      // The kernel dropped events (its buffer overflowed during a long frame): what is held now.
      uint8_t bits[KEY_CNT / 8 + 1] = {};
      if (ioctl(fds_[k], EVIOCGKEY(sizeof bits), bits) >= 0)
        tracker.resync(bits, sizeof bits, &keys);
      ++resyncs_;
      std::fprintf(stderr,
                   "cloudbrush: keyboard: the kernel dropped key events (SYN_DROPPED); key state "
                   "read again\n");
    }
    for (const KeyTransition& key : keys) {
      const bool down = key.down;
      const int code = key.code;
      uint32_t keysym = XKB_KEY_NoSymbol, modifiers = 0;
      if (state_) {
        if (down) keysym = xkb_state_key_get_one_sym(state_, code + kXkbOffset);
        xkb_state_update_key(state_, code + kXkbOffset, down ? XKB_KEY_DOWN : XKB_KEY_UP);
        const auto active = [&](const char* name) {
          return xkb_state_mod_name_is_active(state_, name, XKB_STATE_MODS_EFFECTIVE) > 0;
        };
        modifiers = (active(XKB_MOD_NAME_SHIFT) ? kKeyShift : 0u) |
                    (active(XKB_MOD_NAME_CTRL) ? kKeyCtrl : 0u) |
                    (active(XKB_MOD_NAME_ALT) ? kKeyAlt : 0u);
      } else {
        if (code == KEY_LEFTSHIFT || code == KEY_RIGHTSHIFT) shift_ = down;
        if (code == KEY_LEFTCTRL || code == KEY_RIGHTCTRL) ctrl_ = down;
        if (code == KEY_LEFTALT || code == KEY_RIGHTALT) alt_ = down;
        if (down) keysym = fallbackKeysym(code, shift_);
        modifiers = (shift_ ? kKeyShift : 0u) | (ctrl_ ? kKeyCtrl : 0u) | (alt_ ? kKeyAlt : 0u);
      }
      if (!down || keysym == XKB_KEY_NoSymbol) continue;
      events.push_back({keysym, modifiers});
    }
  }
  return events;
}

}  // namespace cb
