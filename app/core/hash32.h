// One integer hash for every deterministic pattern in the app (brush noise, bristle layouts, the
// renderer's detail noise): Chris Wellons' "lowbias32" from hash-prospector. Header-only so the
// brushes and the renderer inline the same bits.
#pragma once

#include <cstdint>

namespace cb {

constexpr uint32_t hashU32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

}  // namespace cb
