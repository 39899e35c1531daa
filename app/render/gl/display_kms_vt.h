// The kiosk's virtual terminal on the KMS platform (no way out to a shell from the
// keyboard). While locked, the VT on the given descriptor (the process's stdin: the unit's
// TTYPath=/dev/tty7) is brought to the foreground and
//   - handles no keys itself (KDSKBMODE K_OFF): Ctrl+Alt+Fn, Alt+arrows and the console's own
//     Ctrl+Alt+Del go nowhere; the shell still reads the keyboard through evdev
//     (drivers/keyboard/evdev_keyboards.h);
//   - refuses every switch away (VT_SETMODE VT_PROCESS; a release request is answered with
//     VT_RELDISP 0), so `chvt` from another terminal cannot switch either;
//   - draws no console text over the frames (KDSETMODE KD_GRAPHICS).
// The destructor restores the keyboard mode, text mode and automatic switching. One lock per
// process.
#pragma once

#include <memory>
#include <string>

namespace cb {

class VtLock {
 public:
  // Locks the VT open on `fd`. Null with *why when `fd` is not a virtual terminal or an ioctl
  // fails (naming it and the errno text); then nothing was changed.
  static std::unique_ptr<VtLock> lock(int fd, std::string* why);
  ~VtLock();
  VtLock(const VtLock&) = delete;
  VtLock& operator=(const VtLock&) = delete;

  int number() const { return number_; }  // the VT, as in /dev/ttyN

 private:
  VtLock() = default;
  int fd_ = -1;
  int number_ = 0;
  long keyboard_mode_ = 0;
};

}  // namespace cb
