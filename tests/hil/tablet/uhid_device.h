// A HID device made by user space through /dev/uhid (Documentation/hid/uhid.rst): the kernel
// binds its own drivers to it (here: wacom), exactly as it would to a USB tablet. A thread
// answers the kernel's GET_REPORT / SET_REPORT requests (unanswered ones time out after 5 s).
#pragma once

#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace cb::hil {

class UhidDevice {
 public:
  ~UhidDevice() { destroy(); }
  bool create(const std::string& name, const std::vector<uint8_t>& descriptor, uint16_t bus,
              uint16_t vendor, uint16_t product, std::string* error);
  void destroy();
  bool input(const std::vector<uint8_t>& report);
  // Feature reports returned for GET_REPORT, keyed by report ID (data after the ID byte).
  void setFeature(uint8_t id, std::vector<uint8_t> data);
  std::vector<uint8_t> feature(uint8_t id);
  // Every SET_REPORT the kernel sent: report ID then data.
  std::vector<std::vector<uint8_t>> setReports();
  // When each of them arrived (CLOCK_MONOTONIC ns, read as the request reached user space; the
  // requester — a kernel driver or a hidraw HIDIOCSFEATURE — waits for our reply).
  std::vector<int64_t> setReportTimes();
  bool started() const { return started_; }

 private:
  void serve();
  int fd_ = -1;
  std::thread thread_;
  std::atomic<bool> running_{false}, started_{false};
  std::mutex mutex_;
  std::map<uint8_t, std::vector<uint8_t>> features_;
  std::vector<std::vector<uint8_t>> set_reports_;
  std::vector<int64_t> set_report_times_;
};

}  // namespace cb::hil
