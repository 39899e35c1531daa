#include "app/study/frame_timing_stats.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace cb {
namespace {

double ms(int64_t from_ns, int64_t to_ns) {
  return double(to_ns - from_ns) / 1e6;
}

std::string line(const char* label, const Percentiles& p) {
  char text[256];
  if (p.n == 0) {
    std::snprintf(text, sizeof text, "%s: none\n", label);
  } else {
    std::snprintf(text, sizeof text, "%s (%zu): p50 %.1f  p95 %.1f  p99 %.1f  max %.1f ms\n", label,
                  p.n, p.p50, p.p95, p.p99, p.max);
  }
  return text;
}

}  // namespace

Percentiles percentilesOf(std::vector<double> values) {
  Percentiles p;
  p.n = values.size();
  if (values.empty()) return p;
  std::sort(values.begin(), values.end());
  const auto rank = [&](double q) {
    const size_t i = size_t(std::ceil(q * double(values.size())));
    return values[std::clamp<size_t>(i, 1, values.size()) - 1];
  };
  p.p50 = rank(0.50);
  p.p95 = rank(0.95);
  p.p99 = rank(0.99);
  p.max = values.back();
  return p;
}

const std::vector<double>& histogramEdgesMs() {
  // One 60 Hz refresh is 16.7 ms; the anchors of pen latency research (1–2 ms, 7 ms, 25 ms,
  // 40 ms, 65–120 ms end to end: Ng, Annett et al. CHI 2014; Jota et al. CHI 2013).
  static const std::vector<double> edges{4, 8, 12, 16.7, 25, 33.3, 50, 100};
  return edges;
}

FrameTimingStats frameTimingStats(const std::vector<FrameRecord>& frames) {
  FrameTimingStats s;
  s.frames = frames.size();
  s.histogram.assign(histogramEdgesMs().size() + 1, 0);
  s.quarters.resize(4);
  if (frames.empty()) return s;
  s.source = presentSourceName(frames.front().source);
  s.refresh_ms = frames.front().refresh_us / 1000.0;
  s.nominal_refresh = frames.front().nominal_refresh;
  const int64_t t0 = frames.front().present_ns, t1 = frames.back().present_ns;
  const auto quarterOf = [&](int64_t t) {
    return t1 > t0 ? std::min<size_t>(3, size_t(4.0 * double(t - t0) / double(t1 - t0))) : 0;
  };
  std::vector<double> to_present, to_ready, oldest, lift, interval, cpu;
  std::vector<std::vector<double>> by_quarter(4);
  const FrameRecord* previous_ink = nullptr;
  for (const FrameRecord& f : frames) {
    if (presentSourceName(f.source) != s.source) s.source = "mixed";
    cpu.push_back(f.cpu_us / 1000.0);
    const size_t q = quarterOf(f.present_ns);
    ++s.quarters[q].frames;
    if (f.missed_refresh) {
      ++s.missed_frames;
      ++s.quarters[q].missed_frames;
      s.skipped_refreshes += f.skipped_refreshes;
    }
    if (f.hasSample() && !f.hasTimedSample()) ++s.untimed_frames;
    if (!f.hasTimedSample()) {
      previous_ink = nullptr;
      continue;
    }
    if (f.lift) {
      lift.push_back(ms(f.newest_sample_ns, f.present_ns));
      previous_ink = nullptr;
      continue;
    }
    ++s.ink_frames;
    const double latency = ms(f.newest_sample_ns, f.present_ns);
    to_present.push_back(latency);
    by_quarter[q].push_back(latency);
    to_ready.push_back(ms(f.newest_sample_ns, f.ready_ns));
    oldest.push_back(ms(f.oldest_sample_ns, f.present_ns));
    const auto& edges = histogramEdgesMs();
    ++s.histogram[size_t(std::upper_bound(edges.begin(), edges.end(), latency) - edges.begin())];
    if (previous_ink && f.frame == previous_ink->frame + 1)
      interval.push_back(ms(previous_ink->present_ns, f.present_ns));
    previous_ink = &f;
  }
  s.sample_to_present = percentilesOf(to_present);
  s.sample_to_ready = percentilesOf(to_ready);
  s.oldest_to_present = percentilesOf(oldest);
  s.lift_to_present = percentilesOf(lift);
  s.interval = percentilesOf(interval);
  s.cpu = percentilesOf(cpu);
  for (size_t q = 0; q < 4; ++q) s.quarters[q].sample_to_present = percentilesOf(by_quarter[q]);
  return s;
}

std::string formatFrameTimingStats(const FrameTimingStats& s, const std::string& indent) {
  if (s.frames == 0)
    return indent + "frame timing: no Frame records (a journal from before they were written)\n";
  std::string out;
  char text[512];
  std::snprintf(text, sizeof text,
                "frame timing: %zu presented frames, %zu first showing pen samples; present "
                "time: %s; refresh %.1f ms%s\n",
                s.frames, s.ink_frames, s.source.c_str(), s.refresh_ms,
                s.nominal_refresh ? " (assumed: the display reports no mode)" : "");
  out += indent + text;
  if (s.untimed_frames > 0) {
    std::snprintf(text, sizeof text,
                  "  %zu frames showed samples stamped on another clock (a recording replayed at "
                  "its own times): no latency for them\n",
                  s.untimed_frames);
    out += indent + text;
  }
  out += indent + line("  sample -> present, newest sample shown", s.sample_to_present);
  out += indent + line("  sample -> frame ready", s.sample_to_ready);
  out += indent + line("  oldest new sample -> present", s.oldest_to_present);
  out += indent + "  histogram sample -> present (ms):";
  const auto& edges = histogramEdgesMs();
  for (size_t i = 0; i < s.histogram.size(); ++i) {
    if (i == 0)
      std::snprintf(text, sizeof text, " <%g: %zu", edges[0], s.histogram[i]);
    else if (i == edges.size())
      std::snprintf(text, sizeof text, " | >=%g: %zu", edges.back(), s.histogram[i]);
    else
      std::snprintf(text, sizeof text, " | %g-%g: %zu", edges[i - 1], edges[i], s.histogram[i]);
    out += text;
  }
  out += "\n";
  out += indent + line("  frame interval while the pen moves", s.interval);
  out += indent + line("  pen-up: the lift sample -> its cloud shown", s.lift_to_present);
  out += indent + line("  frame CPU time (loop thread)", s.cpu);
  std::snprintf(
      text, sizeof text,
      "  missed refreshes: %zu frames late, %zu refreshes without a new frame (dropped)\n",
      s.missed_frames, s.skipped_refreshes);
  out += indent + text;
  out += indent + "  by quarter of the session:";
  for (size_t q = 0; q < s.quarters.size(); ++q) {
    const auto& quarter = s.quarters[q];
    std::snprintf(text, sizeof text, "%s Q%zu p50 %.1f p95 %.1f ms, %zu/%zu late", q ? " |" : "",
                  q + 1, quarter.sample_to_present.p50, quarter.sample_to_present.p95,
                  quarter.missed_frames, quarter.frames);
    out += text;
  }
  out += "\n";
  return out;
}

}  // namespace cb
