// A USB HID device whose control requests are answered in user space: GadgetFS
// (drivers/usb/gadget/legacy/inode.c, module gadgetfs) on the dummy UDC. Unlike the configfs
// gadget (usb_gadget.h), where the composite framework answers every string descriptor itself,
// GadgetFS answers only GET_DESCRIPTOR(Device/Config), SET_CONFIGURATION and GET_CONFIGURATION
// in the kernel (inode.c gadgetfs_setup) and hands every other request — string descriptors of
// any index, the HID class GET_DESCRIPTOR(Report), SET_IDLE, SET_REPORT — to the process that
// holds /dev/gadget/<udc> open, as a GADGETFS_SETUP event (inode.c ep0_read). A thread answers
// them through `answer`; every request and its answer is logged.
//
// One configuration of HID interfaces numbered 0..n-1; interface i has an interrupt IN endpoint
// 0x81+i and, if asked, an interrupt OUT endpoint 0x01+i whose transfers are read and logged
// (hid-uclogic's XP-Pen/Ugee v2 init writes magic bytes to OUT endpoint 0x03 of interface 2).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace cb::hil {

struct GadgetFsInterface {
  uint8_t subclass = 0, protocol = 0;
  uint16_t report_descriptor_length = 0;  // the HID descriptor's wDescriptorLength
  bool interrupt_out = false;
};

struct GadgetFsConfig {
  uint16_t vendor = 0, product = 0, bcd_device = 0x0100;
  std::vector<GadgetFsInterface> interfaces;  // interface i is number i
  uint16_t max_packet = 64;
};

// One interrupt OUT transfer the host sent.
struct OutTransfer {
  uint8_t endpoint = 0;
  std::vector<uint8_t> data;
};

// One control request as the host sent it, and what the device did.
struct ControlRecord {
  uint8_t request_type = 0, request = 0;
  uint16_t value = 0, index = 0, length = 0;
  enum class Outcome { kAnswered, kStalled, kAcked } outcome = Outcome::kStalled;
  std::vector<uint8_t> data;  // IN: what was sent; OUT: what the host sent
};

std::string describe(const ControlRecord& r);

class GadgetFsDevice {
 public:
  // Reply to an IN request (truncated to wLength by GadgetFS), or nullopt to stall it.
  using Answer = std::function<std::optional<std::vector<uint8_t>>(
      uint8_t request_type, uint8_t request, uint16_t value, uint16_t index, uint16_t length)>;

  ~GadgetFsDevice() { stop(); }
  // Mounts gadgetfs on /dev/gadget (the module must be loaded and the UDC free), writes the
  // descriptors (the host starts enumerating at once) and starts the control thread.
  bool start(const GadgetFsConfig& config, Answer answer, std::string* error);
  // Waits until the host has sent SET_CONFIGURATION and every endpoint is enabled.
  bool waitConfigured(int timeout_ms);
  // Writes one interrupt IN transfer on the interface's endpoint; the write completes when the
  // host has read it (GadgetFS waits for the request's completion, interruptibly), so it is cut
  // off after timeout_ms.
  bool send(size_t interface, const std::vector<uint8_t>& report, int timeout_ms,
            std::string* error);
  std::vector<ControlRecord> controlLog();
  std::vector<OutTransfer> outLog();
  // Closes the endpoint and ep0 files (the device disconnects) and unmounts gadgetfs.
  void stop();

 private:
  struct Endpoint {
    uint8_t address = 0;
    int fd = -1;
  };
  void controlLoop();
  void outLoop(size_t endpoint);
  void handleSetup(uint8_t type, uint8_t request, uint16_t value, uint16_t index, uint16_t length);
  bool enableEndpoints();
  void closeEndpoints();

  GadgetFsConfig config_;
  Answer answer_;
  std::string ep_dir_;
  int ep0_fd_ = -1;
  std::vector<Endpoint> endpoints_;  // IN endpoints first (interface order), then OUT ones
  std::atomic<bool> running_{false}, configured_{false};
  std::thread thread_;
  std::vector<std::thread> out_threads_;
  std::atomic<int> out_threads_running_{0};
  std::mutex mutex_;
  std::vector<ControlRecord> log_;
  std::vector<OutTransfer> out_log_;
  bool mounted_ = false;
};

}  // namespace cb::hil
