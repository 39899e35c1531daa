#include "app/render/gl/display_kms_keyboard.h"

#include <string>

#include <fcntl.h>
#include <linux/input.h>
#include <sys/ioctl.h>
#include <unistd.h>

namespace cb {
namespace {

bool hasBit(const unsigned long* bits, int bit) {
  constexpr int kBitsPerLong = int(sizeof(unsigned long) * 8);
  return (bits[bit / kBitsPerLong] >> (bit % kBitsPerLong)) & 1ul;
}

DisplayEvent::Key keyFromCode(int code) {
  switch (code) {
    case KEY_ESC:
      return DisplayEvent::Key::Escape;
    case KEY_Q:
      return DisplayEvent::Key::Q;
    case KEY_SPACE:
      return DisplayEvent::Key::Space;
    case KEY_S:
      return DisplayEvent::Key::S;
    case KEY_C:
      return DisplayEvent::Key::C;
    case KEY_B:
      return DisplayEvent::Key::B;
    case KEY_M:
      return DisplayEvent::Key::M;
    default:
      return DisplayEvent::Key::Other;
  }
}

}  // namespace

EvdevKeyboards::EvdevKeyboards() {
  for (int i = 0; i < 64; ++i) {
    const std::string path = "/dev/input/event" + std::to_string(i);
    const int fd = open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) continue;
    unsigned long keys[(KEY_MAX + 1) / (sizeof(unsigned long) * 8) + 1] = {};
    if (ioctl(fd, EVIOCGBIT(EV_KEY, sizeof(keys)), keys) >= 0 && hasBit(keys, KEY_ESC)) {
      fds_.push_back(fd);
    } else {
      close(fd);
    }
  }
}

EvdevKeyboards::~EvdevKeyboards() {
  for (int fd : fds_) close(fd);
}

std::vector<DisplayEvent> EvdevKeyboards::poll() {
  std::vector<DisplayEvent> events;
  for (int fd : fds_) {
    input_event ev[32];
    ssize_t n;
    while ((n = read(fd, ev, sizeof(ev))) > 0) {
      for (size_t i = 0; i < size_t(n) / sizeof(input_event); ++i) {
        if (ev[i].type != EV_KEY || ev[i].value != 1) continue;  // 1 = press, 2 = repeat
        DisplayEvent event;
        event.kind = DisplayEvent::Kind::KeyDown;
        event.key = keyFromCode(ev[i].code);
        events.push_back(event);
      }
    }
  }
  return events;
}

}  // namespace cb
