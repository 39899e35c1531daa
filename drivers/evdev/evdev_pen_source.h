// PenSource over libevdev: discovery, CLOCK_MONOTONIC kernel timestamps (EVIOCSCLOCKID),
// SYN_DROPPED resynchronisation, optional exclusive grab, and hotplug through inotify on
// /dev/input (works with or without udevd).
#pragma once

#include <linux/input.h>

#include <memory>
#include <string>

#include "drivers/core/pen_source.h"
#include "drivers/evdev/evdev_pen_state.h"

struct libevdev;

namespace cb {

struct EvdevPenSourceOptions {
  std::string device_path;  // empty: discover (Wacom first)
  std::string input_dir = "/dev/input";
  bool grab = false;  // EVIOCGRAB: no other consumer (X, a console) sees the pen
};

class EvdevPenSource final : public PenSource {
 public:
  explicit EvdevPenSource(EvdevPenSourceOptions options);
  ~EvdevPenSource() override;
  EvdevPenSource(const EvdevPenSource&) = delete;
  EvdevPenSource& operator=(const EvdevPenSource&) = delete;

  const char* backendName() const override { return "evdev"; }
  void poll(int timeout_ms, std::vector<PenSample>& out) override;
  PenConnection connection() const override { return connection_; }
  const PenDeviceInfo& deviceInfo() const override { return info_; }
  std::string serialNumber(std::string* why_none) const override;
  std::string statusMessage() const override { return status_; }
  const std::string& devicePath() const { return path_; }
  uint64_t resyncCount() const { return resyncs_; }

 private:
  void tryOpen();
  void closeDevice(std::vector<PenSample>* out);
  void drain(std::vector<PenSample>& out);
  void seedState();  // copies libevdev's view of the device into the state machine

  EvdevPenSourceOptions options_;
  PenConnection connection_ = PenConnection::kSearching;
  PenDeviceInfo info_{};
  std::string serial_;  // the device's `uniq` as it opened
  std::string status_ = "searching for a pen in /dev/input";
  std::string path_;
  int fd_ = -1;
  int inotify_fd_ = -1;
  libevdev* dev_ = nullptr;
  std::unique_ptr<EvdevPenState> state_;
  int64_t next_scan_ns_ = 0;
  uint64_t resyncs_ = 0;
  input_event sync_report_{};  // the SYN_REPORT that closed a resync (for its timestamp)
};

}  // namespace cb
