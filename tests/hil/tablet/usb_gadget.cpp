#include "tests/hil/tablet/usb_gadget.h"

#include <dirent.h>
#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace cb::hil {
namespace {

bool writeFile(const std::string& path, const void* data, size_t n, std::string* error) {
  int fd = open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0 || write(fd, data, n) != static_cast<ssize_t>(n)) {
    *error = "writing " + path + ": " + std::strerror(errno);
    if (fd >= 0) close(fd);
    return false;
  }
  close(fd);
  return true;
}

bool writeText(const std::string& path, const std::string& text, std::string* error) {
  return writeFile(path, text.data(), text.size(), error);
}

std::string hex(uint16_t v) {
  char b[8];
  std::snprintf(b, sizeof b, "0x%04x", v);
  return b;
}

}  // namespace

UsbGadget::~UsbGadget() {
  remove();
}

bool UsbGadget::create(const std::string& name, const GadgetConfig& c, std::string* error) {
  dir_ = "/sys/kernel/config/usb_gadget/" + name;
  if (mkdir(dir_.c_str(), 0755) != 0 && errno != EEXIST) {
    *error = "mkdir " + dir_ + ": " + std::strerror(errno);
    return false;
  }
  const std::string strings = dir_ + "/strings/0x409", fn = dir_ + "/functions/hid.usb0",
                    cfg = dir_ + "/configs/c.1";
  mkdir(strings.c_str(), 0755);
  mkdir(fn.c_str(), 0755);
  mkdir(cfg.c_str(), 0755);
  return writeText(dir_ + "/idVendor", hex(c.vendor), error) &&
         writeText(dir_ + "/idProduct", hex(c.product), error) &&
         writeText(dir_ + "/bcdUSB", "0x0200", error) &&
         writeText(strings + "/manufacturer", c.manufacturer, error) &&
         writeText(strings + "/product", c.product_name, error) &&
         writeText(strings + "/serialnumber", c.serial, error) &&
         writeText(fn + "/protocol", "0", error) && writeText(fn + "/subclass", "0", error) &&
         writeText(fn + "/report_length", std::to_string(c.report_length), error) &&
         writeFile(fn + "/report_desc", c.report_descriptor.data(), c.report_descriptor.size(),
                   error) &&
         writeText(cfg + "/MaxPower", "100", error) &&
         (symlink(fn.c_str(), (cfg + "/hid.usb0").c_str()) == 0 || errno == EEXIST ||
          (*error = "symlink: " + std::string(std::strerror(errno)), false));
}

bool UsbGadget::bind(std::string* error) {
  std::string udc;
  if (DIR* d = opendir("/sys/class/udc")) {
    while (dirent* e = readdir(d))
      if (e->d_name[0] != '.') udc = e->d_name;
    closedir(d);
  }
  if (udc.empty()) {
    *error = "no USB device controller in /sys/class/udc (is dummy_hcd loaded?)";
    return false;
  }
  return writeText(dir_ + "/UDC", udc, error);
}

bool UsbGadget::unbind(std::string* error) {
  if (hidg_fd_ >= 0) {
    close(hidg_fd_);
    hidg_fd_ = -1;
  }
  return writeText(dir_ + "/UDC", "\n", error);
}

bool UsbGadget::send(const std::vector<uint8_t>& report, int timeout_ms, std::string* error) {
  if (hidg_fd_ < 0) hidg_fd_ = open("/dev/hidg0", O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (hidg_fd_ < 0) {
    *error = std::string("cannot open /dev/hidg0: ") + std::strerror(errno);
    return false;
  }
  pollfd p{hidg_fd_, POLLOUT, 0};
  if (poll(&p, 1, timeout_ms) <= 0) {
    *error = "/dev/hidg0 not writable (is the host reading the interrupt endpoint?)";
    return false;
  }
  if (write(hidg_fd_, report.data(), report.size()) != static_cast<ssize_t>(report.size())) {
    *error = std::string("write /dev/hidg0: ") + std::strerror(errno);
    return false;
  }
  return true;
}

void UsbGadget::remove() {
  if (dir_.empty()) return;
  std::string ignored;
  unbind(&ignored);
  unlink((dir_ + "/configs/c.1/hid.usb0").c_str());
  rmdir((dir_ + "/configs/c.1").c_str());
  rmdir((dir_ + "/functions/hid.usb0").c_str());
  rmdir((dir_ + "/strings/0x409").c_str());
  rmdir(dir_.c_str());
  dir_.clear();
}

}  // namespace cb::hil
