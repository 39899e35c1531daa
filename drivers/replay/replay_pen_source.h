// Plays the pen samples of a recorded journal (drivers/core/journal.h) as if a tablet sent them:
// at the recorded pace against a Clock, or as fast as the consumer polls. For tests, demos and
// the attract loop.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "drivers/core/clock.h"
#include "drivers/core/journal.h"
#include "drivers/core/pen_source.h"

namespace cb {

struct ReplayOptions {
  bool realtime = true;  // false: every poll returns the next batch at once
  bool loop = false;     // start again at the end (attract loop)
  size_t batch = 256;    // samples per poll when not realtime
  // realtime: the clock reads the recording's own time line (a TimelineClock), so each sample
  // plays when the clock reaches its t_ns; false: the first sample plays at the first poll.
  bool timeline = false;
  // realtime: each sample's t_ns becomes the clock's time at which it played, as a tablet's
  // kernel timestamp is the time of the report (latency is measured from it).
  bool restamp = false;
};

class ReplayPenSource final : public PenSource {
 public:
  // Reads the journal at `path`; a corrupt tail is reported in statusMessage(), earlier records
  // still play. `clock` paces realtime playback (MonotonicClock when null).
  ReplayPenSource(const std::string& path, ReplayOptions options, const Clock* clock = nullptr);
  ReplayPenSource(std::vector<JournalRecord> records, ReplayOptions options,
                  const Clock* clock = nullptr);

  const char* backendName() const override { return "replay"; }
  void poll(int timeout_ms, std::vector<PenSample>& out) override;
  PenConnection connection() const override { return connection_; }
  const PenDeviceInfo& deviceInfo() const override { return info_; }
  std::string statusMessage() const override { return status_; }
  std::string serialNumber(std::string* why_none) const override {
    if (why_none) *why_none = "replay: a journal's device record holds no serial";
    return "";
  }
  size_t sampleCount() const { return samples_.size(); }

 private:
  void load(std::vector<JournalRecord> records);

  ReplayOptions options_;
  MonotonicClock default_clock_;
  const Clock* clock_;
  std::vector<PenSample> samples_;
  PenDeviceInfo info_{};
  size_t next_ = 0;
  int64_t start_ns_ = -1;  // clock time at which samples_[0] plays
  PenConnection connection_ = PenConnection::kConnected;
  std::string status_;
};

}  // namespace cb
