// Per-present timing kept in a small ring, so a later frame-timing log can read back the last
// few hundred frames without the display layer doing any I/O.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace cb {

struct FrameTiming {
  uint64_t frame = 0;      // present() count, from 1
  uint64_t submit_ns = 0;  // CLOCK_MONOTONIC when present() was called
  // When the frame reached the screen: on KMS the vblank timestamp of the page-flip event
  // (CLOCK_MONOTONIC, from the kernel); elsewhere the time the swap returned.
  uint64_t shown_ns = 0;
  uint32_t vblank_sequence = 0;  // KMS: the CRTC's vblank counter at the flip
  bool has_vblank = false;       // true when shown_ns/vblank_sequence came from the kernel
};

class FrameTimingRing {
 public:
  static constexpr size_t kCapacity = 256;

  void push(const FrameTiming& timing) {
    entries_[count_ % kCapacity] = timing;
    ++count_;
  }
  // Number of entries held (at most kCapacity).
  size_t size() const { return count_ < kCapacity ? count_ : kCapacity; }
  // Total pushed since creation.
  uint64_t total() const { return count_; }
  // i = 0 is the oldest entry held, size()-1 the newest.
  const FrameTiming& at(size_t i) const {
    const uint64_t oldest = count_ - size();
    return entries_[(oldest + i) % kCapacity];
  }
  const FrameTiming* last() const { return count_ ? &entries_[(count_ - 1) % kCapacity] : nullptr; }

 private:
  std::array<FrameTiming, kCapacity> entries_{};
  uint64_t count_ = 0;
};

}  // namespace cb
