#include "drivers/replay/replay_pen_source.h"

#include <chrono>
#include <thread>

namespace cb {

ReplayPenSource::ReplayPenSource(const std::string& path, ReplayOptions options, const Clock* clock)
    : options_(options), clock_(clock ? clock : &default_clock_) {
  JournalReadResult r = readJournal(path);
  status_ = "replaying " + path;
  if (!r.error.empty()) status_ += " (" + r.error + ")";
  load(std::move(r.records));
}

ReplayPenSource::ReplayPenSource(std::vector<JournalRecord> records, ReplayOptions options,
                                 const Clock* clock)
    : options_(options), clock_(clock ? clock : &default_clock_) {
  status_ = "replaying recorded samples";
  load(std::move(records));
}

void ReplayPenSource::load(std::vector<JournalRecord> records) {
  bool have_info = false;
  for (const JournalRecord& rec : records) {
    if (rec.type == JournalRecordType::kDevice && !have_info) {
      if (auto d = decodeDeviceInfo(rec.payload)) {
        info_ = *d;
        have_info = true;
      }
    } else if (rec.type == JournalRecordType::kPenSample) {
      if (auto s = decodePenSample(rec.payload)) samples_.push_back(*s);
    }
  }
  if (samples_.empty()) {
    connection_ = PenConnection::kFinished;
    status_ += ": no pen samples";
  }
}

void ReplayPenSource::poll(int timeout_ms, std::vector<PenSample>& out) {
  if (connection_ == PenConnection::kFinished) return;
  if (!options_.realtime) {
    for (size_t i = 0; i < options_.batch && next_ < samples_.size(); ++i)
      out.push_back(samples_[next_++]);
  } else {
    if (start_ns_ < 0) start_ns_ = options_.timeline ? samples_.front().t_ns : clock_->nowNs();
    const int64_t t0 = samples_.front().t_ns;
    auto due = [&](size_t i) { return start_ns_ + (samples_[i].t_ns - t0); };
    if (next_ < samples_.size() && due(next_) > clock_->nowNs() && timeout_ms != 0) {
      int64_t wait_ns = due(next_) - clock_->nowNs();
      if (timeout_ms > 0 && wait_ns > int64_t{timeout_ms} * 1000000)
        wait_ns = int64_t{timeout_ms} * 1000000;
      if (clock_ == &default_clock_ || options_.timeline)
        std::this_thread::sleep_for(std::chrono::nanoseconds(wait_ns));
    }
    while (next_ < samples_.size() && due(next_) <= clock_->nowNs()) {
      PenSample sample = samples_[next_];
      if (options_.restamp) sample.t_ns = due(next_);
      out.push_back(sample);
      ++next_;
    }
  }
  if (next_ >= samples_.size()) {
    if (options_.loop) {
      next_ = 0;
      start_ns_ = -1;
    } else {
      connection_ = PenConnection::kFinished;
    }
  }
}

}  // namespace cb
