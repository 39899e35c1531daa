// One presented frame's timing, journalled as a Frame record (JOURNAL.md section 12): when it
// reached the screen, the newest pen sample it shows, when it was begun and ready, the frame
// loop's CPU time on it and whether a refresh was missed. A measurement of the run: a replay
// ignores it for the volume. The frame-timing analogue of PsychoPy's per-flip log.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

namespace cb {

// How present_ns was obtained, best first.
enum class PresentSource : uint8_t {
  kFinish = 0,        // offscreen (surfaceless): glFinish returned
  kSwapFinish = 1,    // a window without completion events (X11): swap + glFinish returned
  kPresentEvent = 2,  // the window system's completion event (X11 Present)
  kFlipEvent = 3,     // KMS: the page-flip event's vblank timestamp (the kernel's)
};
const char* presentSourceName(PresentSource source);

struct FrameRecord {
  uint32_t frame = 0;  // presented frames of this loop before this one
  PresentSource source = PresentSource::kFinish;
  bool missed_refresh = false;     // the frame came later than one refresh after the last one
  bool nominal_refresh = false;    // refresh_us is the assumed 60 Hz, not the display's mode
  bool lift = false;               // the frame shows a lifted stroke's cloud (the pen-up wait)
  uint32_t new_samples = 0;        // pen samples first shown by this frame (saturates at 65535)
  int64_t present_ns = 0;          // the record's t_ns: the frame reached the screen
  int64_t newest_sample_ns = 0;    // kernel timestamp of the newest sample shown (0: none new)
  int64_t oldest_sample_ns = 0;    // of the oldest sample first shown here (0: none new)
  int64_t begin_ns = 0;            // the loop began the frame (took events and pen input)
  int64_t ready_ns = 0;            // drawn and finished (glFinish), before present
  uint32_t cpu_us = 0;             // the loop thread's CPU time from begin to ready
  uint32_t refresh_us = 0;         // the refresh period the missed flag was judged against
  uint32_t skipped_refreshes = 0;  // refreshes passed without a new frame (dropped frames)

  bool hasSample() const { return new_samples > 0; }
  // New samples whose times are on the present's clock (a recording replayed at its own times
  // is not): their latency can be told.
  bool hasTimedSample() const { return new_samples > 0 && newest_sample_ns != 0; }
};

inline constexpr size_t kFrameRecordBytes = 36;
// Times are stored as microseconds before present_ns (the record's t_ns), clamped to u32.
std::vector<uint8_t> encodeFrameRecord(const FrameRecord& record);
// nullopt for a payload of the wrong size.
std::optional<FrameRecord> decodeFrameRecord(int64_t t_ns, const std::vector<uint8_t>& payload);

}  // namespace cb
