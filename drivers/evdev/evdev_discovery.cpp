#include "drivers/evdev/evdev_discovery.h"

#include <fcntl.h>
#include <libevdev/libevdev.h>
#include <linux/input.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace cb {
namespace {

bool testBit(const unsigned long* bits, int bit) {
  constexpr int kBitsPerLong = int(sizeof(unsigned long) * 8);
  return (bits[bit / kBitsPerLong] >> (bit % kBitsPerLong)) & 1ul;
}

// isEvdevPen's test on the node's capability bits straight from the kernel (two ioctls). A
// libevdev initialisation reads every axis, key, LED and switch state besides: 10–140 ms per node
// on the emulated kiosk (tests/hil/kms), paid for the keyboard and the tablet's pad at every plug
// and, while no pen is connected, at every 250 ms rescan.
bool hasPenBits(int fd) {
  constexpr int kBitsPerLong = int(sizeof(unsigned long) * 8);
  unsigned long keys[(KEY_CNT + kBitsPerLong - 1) / kBitsPerLong] = {};
  unsigned long axes[(ABS_CNT + kBitsPerLong - 1) / kBitsPerLong] = {};
  if (ioctl(fd, EVIOCGBIT(EV_KEY, sizeof keys), keys) < 0) return false;
  if (ioctl(fd, EVIOCGBIT(EV_ABS, sizeof axes), axes) < 0) return false;
  return testBit(keys, BTN_TOOL_PEN) && testBit(axes, ABS_X) && testBit(axes, ABS_Y);
}

}  // namespace

bool isEvdevPen(libevdev* dev) {
  return libevdev_has_event_code(dev, EV_KEY, BTN_TOOL_PEN) &&
         libevdev_has_event_code(dev, EV_ABS, ABS_X) && libevdev_has_event_code(dev, EV_ABS, ABS_Y);
}

PenDeviceInfo evdevPenInfo(libevdev* dev) {
  PenDeviceInfo d;
  d.usb_vendor = static_cast<uint16_t>(libevdev_get_id_vendor(dev));
  d.usb_product = static_cast<uint16_t>(libevdev_get_id_product(dev));
  std::snprintf(d.name, sizeof d.name, "%s", libevdev_get_name(dev) ? libevdev_get_name(dev) : "");
  if (const input_absinfo* a = libevdev_get_abs_info(dev, ABS_X)) {
    d.x_max = a->maximum;
    d.x_res = a->resolution;
  }
  if (const input_absinfo* a = libevdev_get_abs_info(dev, ABS_Y)) {
    d.y_max = a->maximum;
    d.y_res = a->resolution;
  }
  if (const input_absinfo* a = libevdev_get_abs_info(dev, ABS_PRESSURE))
    d.pressure_max = a->maximum;
  if (const input_absinfo* a = libevdev_get_abs_info(dev, ABS_TILT_X)) {
    d.tilt_min = a->minimum;
    d.tilt_max = a->maximum;
    d.tilt_res = a->resolution * M_PI / 180.0;  // evdev: units per radian
  }
  if (const input_absinfo* a = libevdev_get_abs_info(dev, ABS_DISTANCE))
    d.distance_max = a->maximum;
  return d;
}

std::vector<EvdevPenCandidate> findEvdevPens(const std::string& dir) {
  std::vector<EvdevPenCandidate> pens;
  std::error_code ec;
  std::vector<std::string> nodes;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("event", 0) == 0) nodes.push_back(e.path().string());
  }
  if (ec == std::errc::permission_denied) {  // the directory itself is closed to this user
    EvdevPenCandidate c;
    c.path = dir;
    c.permission_denied = true;
    pens.push_back(c);
    return pens;
  }
  for (const std::string& path : nodes) {
    int fd = open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
      if (errno == EACCES || errno == EPERM) {
        EvdevPenCandidate c;
        c.path = path;
        c.permission_denied = true;
        pens.push_back(c);
      }
      continue;
    }
    libevdev* dev = nullptr;
    if (!hasPenBits(fd)) {
      close(fd);
      continue;
    }
    if (libevdev_new_from_fd(fd, &dev) == 0) {
      if (isEvdevPen(dev)) pens.push_back({path, evdevPenInfo(dev), false});
      libevdev_free(dev);
    }
    close(fd);
  }
  // Wacom first, then by node path (event2 before event10).
  auto node_number = [](const std::string& p) {
    return std::atoi(p.c_str() + p.rfind("event") + 5);
  };
  std::sort(pens.begin(), pens.end(), [&](const EvdevPenCandidate& a, const EvdevPenCandidate& b) {
    const bool wa = a.info.usb_vendor == 0x056A, wb = b.info.usb_vendor == 0x056A;
    if (wa != wb) return wa;
    if (a.permission_denied != b.permission_denied) return !a.permission_denied;
    return node_number(a.path) < node_number(b.path);
  });
  return pens;
}

}  // namespace cb
