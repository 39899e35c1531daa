#include "app/kiosk/kiosk_heap.h"

#include <malloc.h>

namespace cb {

namespace {
constexpr int kMmapThresholdBytes = 128 * 1024;  // glibc's default, no longer moved
constexpr int kTrimThresholdBytes = 128 * 1024;  // likewise
constexpr int kArenaMax = 4;
}  // namespace

bool setKioskHeapPolicy() {
  // mallopt returns 1 on success.
  return mallopt(M_MMAP_THRESHOLD, kMmapThresholdBytes) == 1 &&
         mallopt(M_TRIM_THRESHOLD, kTrimThresholdBytes) == 1 &&
         mallopt(M_ARENA_MAX, kArenaMax) == 1;
}

}  // namespace cb
