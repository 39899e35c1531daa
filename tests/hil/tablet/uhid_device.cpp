#include "tests/hil/tablet/uhid_device.h"

#include <fcntl.h>
#include <linux/uhid.h>
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "drivers/core/clock.h"

namespace cb::hil {

bool UhidDevice::create(const std::string& name, const std::vector<uint8_t>& descriptor,
                        uint16_t bus, uint16_t vendor, uint16_t product, std::string* error) {
  fd_ = open("/dev/uhid", O_RDWR | O_CLOEXEC);
  if (fd_ < 0) {
    *error = std::string("cannot open /dev/uhid: ") + std::strerror(errno);
    return false;
  }
  uhid_event ev{};
  ev.type = UHID_CREATE2;
  std::snprintf(reinterpret_cast<char*>(ev.u.create2.name), sizeof ev.u.create2.name, "%s",
                name.c_str());
  std::snprintf(reinterpret_cast<char*>(ev.u.create2.uniq), sizeof ev.u.create2.uniq, "cb-hil");
  ev.u.create2.rd_size = static_cast<uint16_t>(descriptor.size());
  ev.u.create2.bus = bus;
  ev.u.create2.vendor = vendor;
  ev.u.create2.product = product;
  std::memcpy(ev.u.create2.rd_data, descriptor.data(), descriptor.size());
  if (write(fd_, &ev, sizeof ev) != static_cast<ssize_t>(sizeof ev)) {
    *error = std::string("UHID_CREATE2 failed: ") + std::strerror(errno);
    close(fd_);
    fd_ = -1;
    return false;
  }
  running_ = true;
  thread_ = std::thread([this] { serve(); });
  return true;
}

void UhidDevice::destroy() {
  if (fd_ < 0) return;
  running_ = false;
  if (thread_.joinable()) thread_.join();
  uhid_event ev{};
  ev.type = UHID_DESTROY;
  (void)!write(fd_, &ev, sizeof ev);
  close(fd_);
  fd_ = -1;
  started_ = false;
}

bool UhidDevice::input(const std::vector<uint8_t>& report) {
  uhid_event ev{};
  ev.type = UHID_INPUT2;
  ev.u.input2.size = static_cast<uint16_t>(report.size());
  std::memcpy(ev.u.input2.data, report.data(), report.size());
  return write(fd_, &ev, sizeof ev) == static_cast<ssize_t>(sizeof ev);
}

void UhidDevice::setFeature(uint8_t id, std::vector<uint8_t> data) {
  std::lock_guard<std::mutex> lock(mutex_);
  features_[id] = std::move(data);
}

std::vector<uint8_t> UhidDevice::feature(uint8_t id) {
  std::lock_guard<std::mutex> lock(mutex_);
  return features_[id];
}

std::vector<int64_t> UhidDevice::setReportTimes() {
  std::lock_guard<std::mutex> lock(mutex_);
  return set_report_times_;
}

std::vector<std::vector<uint8_t>> UhidDevice::setReports() {
  std::lock_guard<std::mutex> lock(mutex_);
  return set_reports_;
}

void UhidDevice::serve() {
  while (running_) {
    pollfd p{fd_, POLLIN, 0};
    if (poll(&p, 1, 50) <= 0) continue;
    uhid_event ev{};
    if (read(fd_, &ev, sizeof ev) <= 0) continue;
    if (ev.type == UHID_START) started_ = true;
    if (std::getenv("CB_HIL_UHID_TRACE") &&
        (ev.type == UHID_GET_REPORT || ev.type == UHID_SET_REPORT))
      std::printf("  uhid: %s report %d type %d\n", ev.type == UHID_GET_REPORT ? "GET" : "SET",
                  ev.type == UHID_GET_REPORT ? ev.u.get_report.rnum : ev.u.set_report.rnum,
                  ev.type == UHID_GET_REPORT ? ev.u.get_report.rtype : ev.u.set_report.rtype);
    if (ev.type == UHID_GET_REPORT) {
      uhid_event reply{};
      reply.type = UHID_GET_REPORT_REPLY;
      reply.u.get_report_reply.id = ev.u.get_report.id;
      std::lock_guard<std::mutex> lock(mutex_);
      auto it = features_.find(ev.u.get_report.rnum);
      if (it == features_.end()) {
        reply.u.get_report_reply.err = EIO;
      } else {
        reply.u.get_report_reply.data[0] = ev.u.get_report.rnum;
        std::memcpy(reply.u.get_report_reply.data + 1, it->second.data(), it->second.size());
        reply.u.get_report_reply.size = static_cast<uint16_t>(it->second.size() + 1);
      }
      (void)!write(fd_, &reply, sizeof reply);
    } else if (ev.type == UHID_SET_REPORT) {
      uhid_event reply{};
      reply.type = UHID_SET_REPORT_REPLY;
      reply.u.set_report_reply.id = ev.u.set_report.id;
      std::lock_guard<std::mutex> lock(mutex_);
      const uint8_t* d = ev.u.set_report.data;
      const size_t n = ev.u.set_report.size;
      set_reports_.emplace_back(d, d + n);
      set_report_times_.push_back(MonotonicClock().nowNs());
      if (n >= 1) features_[ev.u.set_report.rnum] = std::vector<uint8_t>(d + 1, d + n);
      (void)!write(fd_, &reply, sizeof reply);
    }
  }
}

}  // namespace cb::hil
