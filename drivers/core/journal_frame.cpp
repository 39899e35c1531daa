#include "drivers/core/journal_frame.h"

#include <algorithm>
#include <cstring>

namespace cb {
namespace {

enum FrameFlags : uint8_t { kMissed = 1, kNominal = 2, kLift = 4 };

void put32(std::vector<uint8_t>& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
}
void put16(std::vector<uint8_t>& out, uint16_t v) {
  out.push_back(uint8_t(v));
  out.push_back(uint8_t(v >> 8));
}
uint32_t get32(const uint8_t* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}
// Microseconds from `t_ns` to `present_ns`, clamped to what a u32 holds (0xFFFFFFFF: unknown).
uint32_t ageUs(int64_t present_ns, int64_t t_ns) {
  if (t_ns == 0) return 0xFFFFFFFFu;
  const int64_t us = (present_ns - t_ns) / 1000;
  return uint32_t(std::clamp<int64_t>(us, 0, 0xFFFFFFFEll));
}
int64_t fromAge(int64_t present_ns, uint32_t age_us) {
  return age_us == 0xFFFFFFFFu ? 0 : present_ns - int64_t(age_us) * 1000;
}

}  // namespace

const char* presentSourceName(PresentSource source) {
  switch (source) {
    case PresentSource::kFinish:
      return "glFinish (offscreen)";
    case PresentSource::kSwapFinish:
      return "swap + glFinish (no completion events)";
    case PresentSource::kPresentEvent:
      return "Present completion event";
    case PresentSource::kFlipEvent:
      return "page-flip event";
  }
  return "unknown";
}

std::vector<uint8_t> encodeFrameRecord(const FrameRecord& r) {
  std::vector<uint8_t> out;
  out.reserve(kFrameRecordBytes);
  put32(out, r.frame);
  out.push_back(uint8_t(r.source));
  out.push_back(uint8_t((r.missed_refresh ? kMissed : 0) | (r.nominal_refresh ? kNominal : 0) |
                        (r.lift ? kLift : 0)));
  put16(out, uint16_t(std::min<uint32_t>(r.new_samples, 0xFFFF)));
  put32(out, ageUs(r.present_ns, r.newest_sample_ns));
  put32(out, ageUs(r.present_ns, r.oldest_sample_ns));
  put32(out, ageUs(r.present_ns, r.begin_ns));
  put32(out, ageUs(r.present_ns, r.ready_ns));
  put32(out, r.cpu_us);
  put32(out, r.refresh_us);
  put32(out, r.skipped_refreshes);
  return out;
}

std::optional<FrameRecord> decodeFrameRecord(int64_t t_ns, const std::vector<uint8_t>& payload) {
  if (payload.size() != kFrameRecordBytes) return std::nullopt;
  const uint8_t* p = payload.data();
  FrameRecord r;
  r.present_ns = t_ns;
  r.frame = get32(p);
  if (p[4] > uint8_t(PresentSource::kFlipEvent)) return std::nullopt;
  r.source = PresentSource(p[4]);
  r.missed_refresh = p[5] & kMissed;
  r.nominal_refresh = p[5] & kNominal;
  r.lift = p[5] & kLift;
  r.new_samples = uint32_t(p[6]) | uint32_t(p[7]) << 8;
  r.newest_sample_ns = fromAge(t_ns, get32(p + 8));
  r.oldest_sample_ns = fromAge(t_ns, get32(p + 12));
  r.begin_ns = fromAge(t_ns, get32(p + 16));
  r.ready_ns = fromAge(t_ns, get32(p + 20));
  r.cpu_us = get32(p + 24);
  r.refresh_us = get32(p + 28);
  r.skipped_refreshes = get32(p + 32);
  return r;
}

}  // namespace cb
