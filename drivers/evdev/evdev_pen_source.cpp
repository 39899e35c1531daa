#include "drivers/evdev/evdev_pen_source.h"

#include <fcntl.h>
#include <libevdev/libevdev.h>
#include <poll.h>
#include <sys/inotify.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>

#include "drivers/core/clock.h"
#include "drivers/evdev/evdev_discovery.h"

namespace cb {
namespace {

constexpr int64_t kRescanIntervalNs = 250'000'000;  // fallback when inotify misses a change

int64_t nowNs() {
  return MonotonicClock().nowNs();
}

}  // namespace

EvdevPenSource::EvdevPenSource(EvdevPenSourceOptions options) : options_(std::move(options)) {
  inotify_fd_ = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
  if (inotify_fd_ >= 0)
    inotify_add_watch(inotify_fd_, options_.input_dir.c_str(), IN_CREATE | IN_ATTRIB | IN_DELETE);
  tryOpen();
}

EvdevPenSource::~EvdevPenSource() {
  closeDevice(nullptr);
  if (inotify_fd_ >= 0) close(inotify_fd_);
}

void EvdevPenSource::tryOpen() {
  next_scan_ns_ = nowNs() + kRescanIntervalNs;
  std::string path = options_.device_path;
  bool denied = false;
  if (path.empty()) {
    for (const EvdevPenCandidate& c : findEvdevPens(options_.input_dir)) {
      if (c.permission_denied) {
        denied = true;
        continue;
      }
      path = c.path;
      break;
    }
  }
  if (path.empty()) {
    connection_ = denied ? PenConnection::kPermissionDenied : PenConnection::kSearching;
    status_ = denied ? "cannot open the event nodes in " + options_.input_dir +
                           " (permission denied): " + kUdevRuleHint
                     : "no pen found in " + options_.input_dir + "; waiting for one";
    return;
  }
  int fd = open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    connection_ = (err == EACCES || err == EPERM) ? PenConnection::kPermissionDenied
                                                  : PenConnection::kSearching;
    status_ = "cannot open " + path + ": " + std::strerror(err) +
              (connection_ == PenConnection::kPermissionDenied ? std::string("; ") + kUdevRuleHint
                                                               : std::string());
    return;
  }
  libevdev* dev = nullptr;
  if (libevdev_new_from_fd(fd, &dev) != 0 || !isEvdevPen(dev)) {
    if (dev) libevdev_free(dev);
    close(fd);
    connection_ = PenConnection::kSearching;
    status_ = path + " is not a pen (needs BTN_TOOL_PEN and ABS_PRESSURE)";
    return;
  }
  // Kernel timestamps on CLOCK_MONOTONIC, the clock the rest of the program uses.
  int clock_id = CLOCK_MONOTONIC;
  if (ioctl(fd, EVIOCSCLOCKID, &clock_id) != 0) {
    status_ = "EVIOCSCLOCKID failed on " + path + ": " + std::strerror(errno);
  }
  if (options_.grab) libevdev_grab(dev, LIBEVDEV_GRAB);
  fd_ = fd;
  dev_ = dev;
  path_ = path;
  info_ = evdevPenInfo(dev);
  serial_ = libevdev_get_uniq(dev) ? libevdev_get_uniq(dev) : "";
  state_ = std::make_unique<EvdevPenState>(info_);
  seedState();
  connection_ = PenConnection::kConnected;
  status_ = "reading " + path + " (" + info_.name + ")";
}

void EvdevPenSource::seedState() {
  for (uint16_t code : {ABS_X, ABS_Y, ABS_PRESSURE, ABS_TILT_X, ABS_TILT_Y, ABS_DISTANCE, ABS_MISC})
    if (libevdev_has_event_code(dev_, EV_ABS, code))
      state_->setAbs(code, libevdev_get_event_value(dev_, EV_ABS, code));
  for (uint16_t code : {BTN_TOUCH, BTN_STYLUS, BTN_STYLUS2, BTN_TOOL_PEN, BTN_TOOL_PENCIL,
                        BTN_TOOL_BRUSH, BTN_TOOL_AIRBRUSH, BTN_TOOL_RUBBER})
    if (libevdev_has_event_code(dev_, EV_KEY, code))
      state_->setKey(code, libevdev_get_event_value(dev_, EV_KEY, code) != 0);
}

std::string EvdevPenSource::serialNumber(std::string* why_none) const {
  if (connection_ != PenConnection::kConnected) {
    if (why_none) *why_none = "evdev: no device connected";
    return "";
  }
  if (serial_.empty() && why_none)
    *why_none = "evdev: " + path_ + " reports no serial (its uniq is empty)";
  return serial_;
}

void EvdevPenSource::closeDevice(std::vector<PenSample>* out) {
  if (!dev_) return;
  PenSample s;
  if (state_ && out && state_->disconnect(nowNs(), s)) out->push_back(s);
  libevdev_free(dev_);
  close(fd_);
  dev_ = nullptr;
  fd_ = -1;
  state_.reset();
  connection_ = PenConnection::kSearching;
  status_ = path_ + " went away; waiting for a pen";
}

void EvdevPenSource::drain(std::vector<PenSample>& out) {
  input_event ev;
  unsigned flags = LIBEVDEV_READ_FLAG_NORMAL;
  for (;;) {
    int rc = libevdev_next_event(dev_, flags, &ev);
    if (rc == LIBEVDEV_READ_STATUS_SYNC) {
      // SYN_DROPPED: the kernel's buffer overflowed. libevdev re-reads the device state and
      // replays the differences; once it is done the state machine is re-seeded from libevdev's
      // view (the device's true state) and one sample reports it.
      if (flags == LIBEVDEV_READ_FLAG_NORMAL) ++resyncs_;
      flags = LIBEVDEV_READ_FLAG_SYNC;
      if (ev.type == EV_SYN && ev.code == SYN_REPORT) sync_report_ = ev;
      continue;
    }
    if (rc == -EAGAIN) {
      if (flags == LIBEVDEV_READ_FLAG_SYNC) {
        flags = LIBEVDEV_READ_FLAG_NORMAL;  // resync done, back to the live stream
        seedState();
        input_event syn = sync_report_;
        syn.type = EV_SYN;
        syn.code = SYN_REPORT;
        if (syn.input_event_sec == 0 && syn.input_event_usec == 0) {
          const int64_t now = nowNs();
          syn.input_event_sec = now / 1000000000;
          syn.input_event_usec = (now % 1000000000) / 1000;
        }
        PenSample s;
        if (state_->feed(syn, s)) out.push_back(s);
        sync_report_ = input_event{};
        continue;
      }
      return;
    }
    if (rc != LIBEVDEV_READ_STATUS_SUCCESS) {  // -ENODEV: unplugged
      closeDevice(&out);
      return;
    }
    PenSample s;
    if (state_->feed(ev, s)) out.push_back(s);
  }
}

void EvdevPenSource::poll(int timeout_ms, std::vector<PenSample>& out) {
  if (!dev_ && nowNs() >= next_scan_ns_) tryOpen();
  pollfd fds[2];
  int n = 0;
  if (fd_ >= 0) fds[n++] = {fd_, POLLIN, 0};
  if (inotify_fd_ >= 0) fds[n++] = {inotify_fd_, POLLIN, 0};
  int wait = timeout_ms;
  if (!dev_) {  // wake for the periodic rescan
    const int64_t until_scan_ms = (next_scan_ns_ - nowNs()) / 1000000;
    if (wait < 0 || until_scan_ms < wait)
      wait = static_cast<int>(until_scan_ms < 0 ? 0 : until_scan_ms);
  }
  int rc = ::poll(fds, n, wait);
  if (rc <= 0) {
    if (!dev_ && nowNs() >= next_scan_ns_) tryOpen();
    return;
  }
  bool dir_changed = false;
  for (int i = 0; i < n; ++i) {
    if (fds[i].fd == inotify_fd_ && (fds[i].revents & POLLIN)) {
      char buf[4096];
      while (read(inotify_fd_, buf, sizeof buf) > 0) {
      }
      dir_changed = true;
    }
  }
  if (fd_ >= 0 && (fds[0].revents & (POLLIN | POLLERR | POLLHUP))) {
    if (fds[0].revents & (POLLERR | POLLHUP)) {
      drain(out);  // picks up the last events, then -ENODEV closes
      if (dev_) closeDevice(&out);
    } else {
      drain(out);
    }
  }
  if (!dev_ && dir_changed) tryOpen();
}

}  // namespace cb
