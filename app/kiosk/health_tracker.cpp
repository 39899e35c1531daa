#include "app/kiosk/health_tracker.h"

namespace cb {

HealthTracker::HealthTracker(const Clock& clock, int64_t fps_window_ns)
    : clock_(clock),
      fps_window_ns_(fps_window_ns > 0 ? fps_window_ns : 1'000'000'000),
      start_ns_(clock.nowNs()),
      window_start_ns_(start_ns_) {}

void HealthTracker::onFrame() {
  const int64_t now = clock_.nowNs();
  ++window_frames_;
  ++frames_;
  const int64_t elapsed = now - window_start_ns_;
  if (elapsed >= fps_window_ns_) {
    frames_per_second_ = window_frames_ * 1e9 / static_cast<double>(elapsed);
    window_frames_ = 0;
    window_start_ns_ = now;
  }
}

void HealthTracker::onInput() {
  have_input_ = true;
  last_input_ns_ = clock_.nowNs();
}

HealthStatus HealthTracker::snapshot(const DiskSpace* disk, int64_t wall_unix_s) const {
  const int64_t now = clock_.nowNs();
  HealthStatus s;
  s.written_unix_s = wall_unix_s;
  s.uptime_s = (now - start_ns_) * 1e-9;
  // A loop that stopped drawing shows 0, not the last good rate.
  s.frames_per_second = (now - window_start_ns_ > 2 * fps_window_ns_) ? 0.0 : frames_per_second_;
  if (have_input_) s.last_input_age_s = (now - last_input_ns_) * 1e-9;
  s.device_state = device_state_;
  if (disk) {
    s.disk_free_bytes = disk->free_bytes;
    s.disk_total_bytes = disk->total_bytes;
  }
  s.last_error = last_error_;
  s.storage = storage_;
  s.frames = frames_;
  s.counts = counts_;
  return s;
}

}  // namespace cb
