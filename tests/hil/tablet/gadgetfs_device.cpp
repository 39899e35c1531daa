#include "tests/hil/tablet/gadgetfs_device.h"

#include <dirent.h>
#include <fcntl.h>
#include <linux/usb/ch9.h>
#include <linux/usb/gadgetfs.h>
#include <poll.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>

namespace cb::hil {
namespace {

constexpr const char* kMountPoint = "/dev/gadget";
// dummy_hcd's first bulk-capable IN endpoint (drivers/usb/gadget/udc/dummy_hcd.c ep_info[]);
// dummy_enable accepts an interrupt descriptor on a "-bulk" endpoint.
constexpr const char* kEndpointName = "ep1in-bulk";
constexpr uint8_t kEndpointAddress = 0x81;

void put16(std::vector<uint8_t>& b, uint16_t v) {
  b.push_back(v & 0xFF);
  b.push_back(v >> 8);
}

// Configuration 1: interface 0 (HID), its HID descriptor, one interrupt IN endpoint.
// bInterval: 1 ms at full speed (frames), 2^(4-1) microframes = 1 ms at high speed.
std::vector<uint8_t> configDescriptor(const GadgetFsConfig& c, bool high_speed) {
  std::vector<uint8_t> b = {9, USB_DT_CONFIG, 0, 0, 1, 1, 0, USB_CONFIG_ATT_ONE, 50};
  const std::vector<uint8_t> iface = {
      9, USB_DT_INTERFACE, 0, 0, 1, 3, c.interface_subclass, c.interface_protocol, 0};
  b.insert(b.end(), iface.begin(), iface.end());
  b.insert(b.end(), {9, 0x21, 0x11, 0x01, 0, 1, 0x22});  // HID 1.11, one Report descriptor
  put16(b, c.report_descriptor_length);
  b.insert(b.end(), {7, USB_DT_ENDPOINT, kEndpointAddress, USB_ENDPOINT_XFER_INT});
  put16(b, c.max_packet);
  b.push_back(high_speed ? 4 : 1);
  b[2] = b.size() & 0xFF;
  b[3] = b.size() >> 8;
  return b;
}

std::vector<uint8_t> deviceDescriptor(const GadgetFsConfig& c) {
  std::vector<uint8_t> b = {18, USB_DT_DEVICE, 0x00, 0x02, 0, 0, 0, 64};
  put16(b, c.vendor);
  put16(b, c.product);
  put16(b, c.bcd_device);
  b.insert(b.end(), {1, 2, 3, 1});  // iManufacturer, iProduct, iSerialNumber, one configuration
  return b;
}

void onTimeout(int) {}

}  // namespace

std::string describe(const ControlRecord& r) {
  char b[96];
  std::snprintf(b, sizeof b, "%02x %02x wValue %04x wIndex %04x wLength %u -> ", r.request_type,
                r.request, r.value, r.index, r.length);
  std::string s = b;
  if (r.outcome == ControlRecord::Outcome::kStalled) return s + "stall";
  s += r.outcome == ControlRecord::Outcome::kAcked ? "ack" : "answered";
  if (!r.data.empty()) {
    s += " " + std::to_string(r.data.size()) + " bytes";
    for (size_t i = 0; i < r.data.size() && i < 20; ++i) {
      std::snprintf(b, sizeof b, " %02x", r.data[i]);
      s += b;
    }
    if (r.data.size() > 20) s += " ...";
  }
  return s;
}

bool GadgetFsDevice::start(const GadgetFsConfig& config, Answer answer, std::string* error) {
  config_ = config;
  answer_ = std::move(answer);
  mkdir(kMountPoint, 0755);
  if (mount("gadgetfs", kMountPoint, "gadgetfs", 0, nullptr) != 0 && errno != EBUSY) {
    *error = std::string("mount -t gadgetfs: ") + std::strerror(errno);
    return false;
  }
  mounted_ = true;
  // gadgetfs_fill_super names the ep0 file after the free UDC (usb_get_gadget_udc_name).
  std::string chip;
  if (DIR* d = opendir(kMountPoint)) {
    while (dirent* e = readdir(d))
      if (e->d_name[0] != '.' && std::strncmp(e->d_name, "ep", 2) != 0) chip = e->d_name;
    closedir(d);
  }
  if (chip.empty()) {
    *error = "gadgetfs shows no UDC file (is dummy_hcd loaded and its UDC free?)";
    return false;
  }
  ep_dir_ = kMountPoint;
  ep0_fd_ = open((ep_dir_ + "/" + chip).c_str(), O_RDWR | O_CLOEXEC);
  if (ep0_fd_ < 0) {
    *error = "open " + ep_dir_ + "/" + chip + ": " + std::strerror(errno);
    return false;
  }
  // inode.c dev_config: tag 0, full-speed config, high-speed config, device descriptor.
  std::vector<uint8_t> w = {0, 0, 0, 0};
  for (const auto& part :
       {configDescriptor(config, false), configDescriptor(config, true), deviceDescriptor(config)})
    w.insert(w.end(), part.begin(), part.end());
  if (write(ep0_fd_, w.data(), w.size()) != static_cast<ssize_t>(w.size())) {
    *error = std::string("writing the descriptors to ep0: ") + std::strerror(errno);
    return false;
  }
  struct sigaction sa {};
  sa.sa_handler = onTimeout;  // no SA_RESTART: the endpoint write returns EINTR
  sigemptyset(&sa.sa_mask);
  sigaction(SIGUSR2, &sa, nullptr);
  running_ = true;
  thread_ = std::thread([this] { controlLoop(); });
  return true;
}

void GadgetFsDevice::controlLoop() {
  usb_gadgetfs_event events[5];
  while (running_) {
    pollfd p{ep0_fd_, POLLIN, 0};
    if (poll(&p, 1, 50) <= 0) continue;
    const ssize_t n = read(ep0_fd_, events, sizeof events);
    if (n < 0) continue;  // EIDRM (a request aborted) and the like: read on
    for (size_t i = 0; i < static_cast<size_t>(n) / sizeof events[0]; ++i) {
      const usb_gadgetfs_event& e = events[i];
      if (e.type == GADGETFS_DISCONNECT) configured_ = false;
      if (e.type != GADGETFS_SETUP) continue;
      const usb_ctrlrequest& c = e.u.setup;
      handleSetup(c.bRequestType, c.bRequest, c.wValue, c.wIndex, c.wLength);
    }
  }
}

// An IN request gets the answer or a stall (a zero-length read in the setup state halts ep0,
// inode.c ep0_read); an OUT request's data stage is read, which acknowledges it. On
// SET_CONFIGURATION the interrupt endpoint is enabled before the status stage.
void GadgetFsDevice::handleSetup(uint8_t type, uint8_t request, uint16_t value, uint16_t index,
                                 uint16_t length) {
  ControlRecord rec;
  rec.request_type = type;
  rec.request = request;
  rec.value = value;
  rec.index = index;
  rec.length = length;
  if (type & USB_DIR_IN) {
    auto reply = answer_(type, request, value, index, length);
    if (reply) {
      if (reply->size() > length) reply->resize(length);
      if (write(ep0_fd_, reply->data(), reply->size()) >= 0) {
        rec.outcome = ControlRecord::Outcome::kAnswered;
        rec.data = *reply;
      }
    } else {
      char ignored;
      (void)!read(ep0_fd_, &ignored, 0);
    }
  } else {
    if (type == 0 && request == USB_REQ_SET_CONFIGURATION) {
      if (value != 0) enableEndpoint();
    }
    std::vector<uint8_t> data(length);
    const ssize_t got = read(ep0_fd_, data.data(), length);
    if (got >= 0) {
      data.resize(got);
      rec.outcome = ControlRecord::Outcome::kAcked;
      rec.data = data;
      if (type == 0 && request == USB_REQ_SET_CONFIGURATION)
        configured_ = value != 0 && ep_fd_ >= 0;
    }
  }
  std::lock_guard<std::mutex> lock(mutex_);
  log_.push_back(rec);
}

bool GadgetFsDevice::enableEndpoint() {
  if (ep_fd_ >= 0) close(ep_fd_);
  ep_fd_ = open((ep_dir_ + "/" + kEndpointName).c_str(), O_RDWR | O_CLOEXEC);
  if (ep_fd_ < 0) return false;
  // inode.c ep_config: tag 1, the full-speed then the high-speed endpoint descriptor.
  std::vector<uint8_t> w = {1, 0, 0, 0};
  for (bool hs : {false, true}) {
    const std::vector<uint8_t> c = configDescriptor(config_, hs);
    w.insert(w.end(), c.end() - 7, c.end());
  }
  if (write(ep_fd_, w.data(), w.size()) != static_cast<ssize_t>(w.size())) {
    close(ep_fd_);
    ep_fd_ = -1;
    return false;
  }
  return true;
}

bool GadgetFsDevice::waitConfigured(int timeout_ms) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  while (!configured_ && std::chrono::steady_clock::now() < end)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  return configured_;
}

bool GadgetFsDevice::send(const std::vector<uint8_t>& report, int timeout_ms, std::string* error) {
  if (!configured_ || ep_fd_ < 0) {
    *error = "the host has not configured the device";
    return false;
  }
  // The write sleeps until the host's interrupt URB takes the data (inode.c ep_io,
  // wait_for_completion_interruptible): a timer signal to this thread cuts it off.
  sigevent sev{};
  sev.sigev_notify = SIGEV_THREAD_ID;
  sev.sigev_signo = SIGUSR2;
  sev._sigev_un._tid = static_cast<pid_t>(syscall(SYS_gettid));
  timer_t timer;
  if (timer_create(CLOCK_MONOTONIC, &sev, &timer) != 0) {
    *error = std::string("timer_create: ") + std::strerror(errno);
    return false;
  }
  itimerspec its{};
  its.it_value.tv_sec = timeout_ms / 1000;
  its.it_value.tv_nsec = (timeout_ms % 1000) * 1000000L;
  timer_settime(timer, 0, &its, nullptr);
  const ssize_t n = write(ep_fd_, report.data(), report.size());
  const int err = errno;
  timer_delete(timer);
  if (n != static_cast<ssize_t>(report.size())) {
    *error = std::string("interrupt IN write: ") +
             (err == EINTR ? "the host did not read it within " + std::to_string(timeout_ms) +
                                 " ms (is the HID device open?)"
                           : std::strerror(err));
    return false;
  }
  return true;
}

std::vector<ControlRecord> GadgetFsDevice::controlLog() {
  std::lock_guard<std::mutex> lock(mutex_);
  return log_;
}

void GadgetFsDevice::stop() {
  running_ = false;
  if (thread_.joinable()) thread_.join();
  if (ep_fd_ >= 0) close(ep_fd_);
  if (ep0_fd_ >= 0) close(ep0_fd_);  // gadgetfs unregisters its driver: the host sees an unplug
  ep_fd_ = ep0_fd_ = -1;
  configured_ = false;
  if (mounted_) umount2(kMountPoint, MNT_DETACH);
  mounted_ = false;
}

}  // namespace cb::hil
