#include "tests/hil/tablet/gadgetfs_device.h"

#include <dirent.h>
#include <fcntl.h>
#include <linux/usb/ch9.h>
#include <linux/usb/gadgetfs.h>
#include <poll.h>
#include <pthread.h>
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
// dummy_hcd's endpoints (drivers/usb/gadget/udc/dummy_hcd.c ep_info[]) given to interfaces in
// order: bulk-capable IN ones (dummy_enable accepts an interrupt descriptor on a "-bulk"
// endpoint; the lettered ones are bulk-or-interrupt) and the lettered OUT ones. dummy_hcd finds
// an endpoint by the address in its descriptor (find_endpoint), not by its name.
constexpr const char* kInNames[] = {"ep1in-bulk", "ep-bin", "ep-ein", "ep-gin"};
constexpr const char* kOutNames[] = {"ep-aout", "ep-cout", "ep-dout", "ep-fout"};
constexpr size_t kMaxInterfaces = sizeof kInNames / sizeof kInNames[0];

void put16(std::vector<uint8_t>& b, uint16_t v) {
  b.push_back(v & 0xFF);
  b.push_back(v >> 8);
}

// An interrupt endpoint descriptor. bInterval: 1 ms at full speed (frames), 2^(4-1)
// microframes = 1 ms at high speed.
std::vector<uint8_t> endpointDescriptor(uint8_t address, uint16_t max_packet, bool high_speed) {
  std::vector<uint8_t> b = {7, USB_DT_ENDPOINT, address, USB_ENDPOINT_XFER_INT};
  put16(b, max_packet);
  b.push_back(high_speed ? 4 : 1);
  return b;
}

// Configuration 1: each interface (HID), its HID descriptor, its interrupt IN endpoint and,
// if asked, its interrupt OUT endpoint.
std::vector<uint8_t> configDescriptor(const GadgetFsConfig& c, bool high_speed) {
  const auto count = static_cast<uint8_t>(c.interfaces.size());
  std::vector<uint8_t> b = {9, USB_DT_CONFIG, 0, 0, count, 1, 0, USB_CONFIG_ATT_ONE, 50};
  for (uint8_t i = 0; i < count; ++i) {
    const GadgetFsInterface& f = c.interfaces[i];
    const uint8_t endpoints = f.interrupt_out ? 2 : 1;
    b.insert(b.end(), {9, USB_DT_INTERFACE, i, 0, endpoints, 3, f.subclass, f.protocol, 0});
    b.insert(b.end(), {9, 0x21, 0x11, 0x01, 0, 1, 0x22});  // HID 1.11, one Report descriptor
    put16(b, f.report_descriptor_length);
    const auto in = endpointDescriptor(USB_DIR_IN | (i + 1), c.max_packet, high_speed);
    b.insert(b.end(), in.begin(), in.end());
    if (f.interrupt_out) {
      const auto out = endpointDescriptor(i + 1, c.max_packet, high_speed);
      b.insert(b.end(), out.begin(), out.end());
    }
  }
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
  if (config.interfaces.empty() || config.interfaces.size() > kMaxInterfaces) {
    *error = "GadgetFS device: 1 to " + std::to_string(kMaxInterfaces) + " interfaces";
    return false;
  }
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
// SET_CONFIGURATION the interrupt endpoints are enabled before the status stage.
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
      if (value != 0) enableEndpoints();
    }
    std::vector<uint8_t> data(length);
    const ssize_t got = read(ep0_fd_, data.data(), length);
    if (got >= 0) {
      data.resize(got);
      rec.outcome = ControlRecord::Outcome::kAcked;
      rec.data = data;
      if (type == 0 && request == USB_REQ_SET_CONFIGURATION)
        configured_ = value != 0 && !endpoints_.empty();
    }
  }
  std::lock_guard<std::mutex> lock(mutex_);
  log_.push_back(rec);
}

// inode.c ep_config: tag 1, then the full-speed and the high-speed endpoint descriptor. A
// reader thread per OUT endpoint keeps a read queued, so the host's transfers complete.
bool GadgetFsDevice::enableEndpoints() {
  closeEndpoints();
  std::vector<Endpoint> eps;
  std::vector<std::string> names;
  for (size_t i = 0; i < config_.interfaces.size(); ++i) {
    eps.push_back({static_cast<uint8_t>(USB_DIR_IN | (i + 1)), -1});
    names.push_back(kInNames[i]);
  }
  for (size_t i = 0, out = 0; i < config_.interfaces.size(); ++i)
    if (config_.interfaces[i].interrupt_out) {
      eps.push_back({static_cast<uint8_t>(i + 1), -1});
      names.push_back(kOutNames[out++]);
    }
  for (size_t e = 0; e < eps.size(); ++e) {
    eps[e].fd = open((ep_dir_ + "/" + names[e]).c_str(), O_RDWR | O_CLOEXEC);
    std::vector<uint8_t> w = {1, 0, 0, 0};
    for (bool hs : {false, true}) {
      const auto d = endpointDescriptor(eps[e].address, config_.max_packet, hs);
      w.insert(w.end(), d.begin(), d.end());
    }
    if (eps[e].fd < 0 || write(eps[e].fd, w.data(), w.size()) != static_cast<ssize_t>(w.size())) {
      for (const Endpoint& ep : eps)
        if (ep.fd >= 0) close(ep.fd);
      return false;
    }
  }
  endpoints_ = eps;
  for (size_t e = 0; e < endpoints_.size(); ++e)
    if (!(endpoints_[e].address & USB_DIR_IN)) {
      ++out_threads_running_;
      out_threads_.emplace_back([this, e] { outLoop(e); });
    }
  return true;
}

void GadgetFsDevice::outLoop(size_t endpoint) {
  const Endpoint ep = endpoints_[endpoint];
  uint8_t buf[512];
  while (running_) {
    const ssize_t n = read(ep.fd, buf, sizeof buf);  // EINTR: stop() wants the thread back
    if (n < 0 && errno != EINTR) break;
    if (n < 0) continue;
    std::lock_guard<std::mutex> lock(mutex_);
    out_log_.push_back({ep.address, std::vector<uint8_t>(buf, buf + n)});
  }
  --out_threads_running_;
}

// Stops the OUT readers (a SIGUSR2 interrupts a read that waits for the host, until each has
// left) and closes every endpoint file.
void GadgetFsDevice::closeEndpoints() {
  const bool was_running = running_;
  running_ = false;
  while (out_threads_running_ > 0) {
    for (std::thread& t : out_threads_) pthread_kill(t.native_handle(), SIGUSR2);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  for (std::thread& t : out_threads_) t.join();
  out_threads_.clear();
  running_ = was_running;
  for (const Endpoint& ep : endpoints_)
    if (ep.fd >= 0) close(ep.fd);
  endpoints_.clear();
}

bool GadgetFsDevice::waitConfigured(int timeout_ms) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  while (!configured_ && std::chrono::steady_clock::now() < end)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  return configured_;
}

bool GadgetFsDevice::send(size_t interface, const std::vector<uint8_t>& report, int timeout_ms,
                          std::string* error) {
  if (!configured_ || interface >= config_.interfaces.size() || endpoints_.size() <= interface) {
    *error = "the host has not configured the device (or it has no interface " +
             std::to_string(interface) + ")";
    return false;
  }
  const int fd = endpoints_[interface].fd;
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
  const ssize_t n = write(fd, report.data(), report.size());
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

std::vector<OutTransfer> GadgetFsDevice::outLog() {
  std::lock_guard<std::mutex> lock(mutex_);
  return out_log_;
}

void GadgetFsDevice::stop() {
  running_ = false;
  if (thread_.joinable()) thread_.join();
  closeEndpoints();
  if (ep0_fd_ >= 0) close(ep0_fd_);  // gadgetfs unregisters its driver: the host sees an unplug
  ep0_fd_ = -1;
  configured_ = false;
  if (mounted_) umount2(kMountPoint, MNT_DETACH);
  mounted_ = false;
}

}  // namespace cb::hil
