// A PenSource read on a thread of its own: the device backend (evdev, hidapi) is polled
// continuously there and its samples wait in a queue until the frame loop takes them. A frame
// that takes long (a slow machine, a stroke's mapping, an emulated CPU) then loses nothing: the
// kernel's evdev client buffer holds only a few packets (64–128 events, about 0.1 s of a pen
// reporting at 100–200 Hz) and overflows into SYN_DROPPED, and a device unplugged before its
// buffer was read takes its last events with it (evdev_read returns -ENODEV at once). A newly
// plugged tablet is also opened as its node appears, not at the next frame.
//
// What the caller sees is unchanged: samples keep their kernel timestamps, and connection(),
// deviceInfo(), statusMessage() and serialNumber() describe the device as of the caller's last
// poll(). poll() returns the queued samples of one connection state at a time, so a caller that
// polls once per frame still sees every unplug and replug (searching, then connected) in order,
// with the proximity-out sample of the unplug in the poll that reports "searching".
// inputWaiting() says, without the lock, whether anything is queued: a frame drawn in slices asks
// it between them (app/shell/kiosk/attract_screen.h).
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "drivers/core/pen_source.h"

namespace cb {

struct ThreadedPenSourceOptions {
  int poll_ms = 20;  // the reader thread's wait in the backend's poll (also its stop latency)
  // Samples kept when the caller stops taking them; beyond this the oldest go (counted).
  size_t max_queued_samples = 1 << 16;
};

class ThreadedPenSource final : public PenSource {
 public:
  // Takes the backend; its methods are called only from the reader thread from now on.
  explicit ThreadedPenSource(std::unique_ptr<PenSource> backend,
                             ThreadedPenSourceOptions options = {});
  ~ThreadedPenSource() override;  // stops the thread, then closes the backend
  ThreadedPenSource(const ThreadedPenSource&) = delete;
  ThreadedPenSource& operator=(const ThreadedPenSource&) = delete;

  const char* backendName() const override { return backend_name_; }
  void poll(int timeout_ms, std::vector<PenSample>& out) override;
  // Set by the reader thread as it queues news, cleared by poll() when it took the last of it.
  bool inputWaiting() const override { return waiting_.load(std::memory_order_acquire); }
  PenConnection connection() const override { return shown_.connection; }
  const PenDeviceInfo& deviceInfo() const override { return shown_.info; }
  std::string statusMessage() const override { return shown_.status; }
  std::string serialNumber(std::string* why_none) const override;
  // Samples dropped because the queue was full (the caller did not poll for a long time).
  uint64_t droppedSamples() const;

 private:
  // The backend's state after one of its polls.
  struct State {
    PenConnection connection = PenConnection::kSearching;
    PenDeviceInfo info{};
    std::string status, serial, why_no_serial;
    bool sameAs(const State& o) const {
      return connection == o.connection && status == o.status && serial == o.serial;
    }
  };
  struct Batch {
    State state;
    std::vector<PenSample> samples;
  };
  static State stateOf(const PenSource& backend);
  void readLoop();

  std::unique_ptr<PenSource> backend_;
  const char* backend_name_;
  ThreadedPenSourceOptions options_;
  State shown_;  // the caller's view; touched only by the caller's thread
  mutable std::mutex mutex_;
  std::condition_variable arrived_;
  std::deque<Batch> queue_;  // guarded by mutex_
  size_t queued_samples_ = 0;
  uint64_t dropped_ = 0;
  bool stop_ = false;
  std::atomic<bool> waiting_{false};  // !queue_.empty(), readable without the mutex
  std::thread thread_;                // last: starts after everything above is set up
};

}  // namespace cb
