#include "app/shell/frame_stamper.h"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "app/render/gl/display.h"

namespace cb {
namespace {

int64_t threadCpuNs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return int64_t(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

// A frame is late when it comes more than half a refresh after the one it should have met.
constexpr double kLateFraction = 1.5;
// A sample stamped later than the present, or more than this before it, is on another clock (a
// recording replayed at its own times): its count is kept, its time is not.
constexpr int64_t kMaxSampleAgeNs = 60'000'000'000;
// Without the display's mode (offscreen, X11) frames are judged against a 60 Hz refresh.
constexpr uint32_t kNominalRefreshUs = 16667;

}  // namespace

FrameStamper::FrameStamper(const Display& display) : display_(display) {
  const std::string platform = display.platformName();
  source_ = platform == "kms"   ? PresentSource::kFlipEvent
            : platform == "x11" ? PresentSource::kSwapFinish
                                : PresentSource::kFinish;
  std::string why;
  const std::optional<double> hz = display.refreshHz(&why);
  nominal_refresh_ = !hz || *hz <= 0.0;
  refresh_us_ = nominal_refresh_ ? kNominalRefreshUs : uint32_t(std::lround(1e6 / *hz));
}

void FrameStamper::begin(int64_t now_ns) {
  begin_ns_ = now_ns;
  cpu_begin_ns_ = threadCpuNs();
}

void FrameStamper::samplesTaken(const std::vector<PenSample>& samples) {
  for (const PenSample& s : samples) {
    if (new_samples_ == 0 || s.t_ns < oldest_ns_) oldest_ns_ = s.t_ns;
    if (new_samples_ == 0 || s.t_ns > newest_ns_) newest_ns_ = s.t_ns;
    ++new_samples_;
  }
}

void FrameStamper::ready(int64_t now_ns) {
  ready_ns_ = now_ns;
  cpu_ready_ns_ = threadCpuNs();
}

FrameRecord FrameStamper::presented(bool after_idle, bool lift, int64_t clock_offset_ns) {
  const FrameTiming* timing = display_.frameTimings().last();
  FrameRecord r;
  r.frame = frames_++;
  r.source = source_;
  // The first KMS frame sets the mode: no flip event for it.
  if (source_ == PresentSource::kFlipEvent && !(timing && timing->has_vblank))
    r.source = PresentSource::kSwapFinish;
  r.lift = lift;
  r.refresh_us = refresh_us_;
  r.nominal_refresh = nominal_refresh_;
  const int64_t present = timing ? int64_t(timing->shown_ns) : ready_ns_;
  if (last_present_ns_ > 0 && !after_idle) {
    const bool counted =
        timing && timing->has_vblank && timing->vblank_sequence != 0 && last_sequence_ != 0;
    if (counted) {  // the kernel's vblank counter says how many refreshes passed
      const uint32_t passed = timing->vblank_sequence - last_sequence_;
      r.skipped_refreshes = passed > 1 ? passed - 1 : 0;
    } else {
      const double periods = double(present - last_present_ns_) / (1e3 * refresh_us_);
      if (periods > kLateFraction) r.skipped_refreshes = uint32_t(std::lround(periods)) - 1;
    }
    r.missed_refresh = r.skipped_refreshes > 0;
  }
  last_present_ns_ = present;
  last_sequence_ = timing ? timing->vblank_sequence : 0;
  r.present_ns = present + clock_offset_ns;
  r.begin_ns = begin_ns_ + clock_offset_ns;
  r.ready_ns = ready_ns_ + clock_offset_ns;
  r.cpu_us = uint32_t(std::max<int64_t>(0, cpu_ready_ns_ - cpu_begin_ns_) / 1000);
  r.new_samples = new_samples_;
  const auto onThisClock = [&](int64_t t) {
    return t <= r.present_ns && r.present_ns - t < kMaxSampleAgeNs;
  };
  if (new_samples_ > 0 && onThisClock(newest_ns_) && onThisClock(oldest_ns_)) {
    r.newest_sample_ns = newest_ns_;
    r.oldest_sample_ns = oldest_ns_;
  }
  new_samples_ = 0;
  return r;
}

}  // namespace cb
