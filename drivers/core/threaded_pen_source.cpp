#include "drivers/core/threaded_pen_source.h"

#include <algorithm>
#include <chrono>

namespace cb {

ThreadedPenSource::State ThreadedPenSource::stateOf(const PenSource& backend) {
  State s;
  s.connection = backend.connection();
  s.info = backend.deviceInfo();
  s.status = backend.statusMessage();
  s.serial = backend.serialNumber(&s.why_no_serial);
  return s;
}

ThreadedPenSource::ThreadedPenSource(std::unique_ptr<PenSource> backend,
                                     ThreadedPenSourceOptions options)
    : backend_(std::move(backend)),
      backend_name_(backend_->backendName()),
      options_(options),
      shown_(stateOf(*backend_)),
      thread_([this] { readLoop(); }) {}

ThreadedPenSource::~ThreadedPenSource() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  thread_.join();
}

void ThreadedPenSource::readLoop() {
  State last = stateOf(*backend_);
  std::vector<PenSample> got;
  for (;;) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (stop_) return;
    }
    got.clear();
    backend_->poll(options_.poll_ms, got);
    State now = stateOf(*backend_);
    if (got.empty() && now.sameAs(last)) continue;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      // A batch per connection state; within one, the newest status and device info.
      if (queue_.empty() || queue_.back().state.connection != now.connection)
        queue_.push_back({now, {}});
      else
        queue_.back().state = now;
      std::vector<PenSample>& into = queue_.back().samples;
      into.insert(into.end(), got.begin(), got.end());
      queued_samples_ += got.size();
      // The caller has not polled for a long time: the oldest samples go (state changes stay).
      for (Batch& b : queue_) {
        if (queued_samples_ <= options_.max_queued_samples) break;
        const size_t drop =
            std::min(b.samples.size(), queued_samples_ - options_.max_queued_samples);
        b.samples.erase(b.samples.begin(), b.samples.begin() + long(drop));
        queued_samples_ -= drop;
        dropped_ += drop;
      }
      waiting_.store(true, std::memory_order_release);
    }
    arrived_.notify_all();
    last = std::move(now);
  }
}

void ThreadedPenSource::poll(int timeout_ms, std::vector<PenSample>& out) {
  std::unique_lock<std::mutex> lock(mutex_);
  const auto has_news = [this] { return !queue_.empty() || stop_; };
  if (timeout_ms < 0)
    arrived_.wait(lock, has_news);
  else if (timeout_ms > 0)
    arrived_.wait_for(lock, std::chrono::milliseconds(timeout_ms), has_news);
  if (queue_.empty()) return;
  // One connection state per poll: every state the backend went through is seen in order.
  Batch& b = queue_.front();
  out.insert(out.end(), b.samples.begin(), b.samples.end());
  queued_samples_ -= b.samples.size();
  shown_ = std::move(b.state);
  queue_.pop_front();
  waiting_.store(!queue_.empty(), std::memory_order_release);
}

std::string ThreadedPenSource::serialNumber(std::string* why_none) const {
  if (shown_.serial.empty() && why_none) *why_none = shown_.why_no_serial;
  return shown_.serial;
}

uint64_t ThreadedPenSource::droppedSamples() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return dropped_;
}

}  // namespace cb
