#include "app/brush/billow_profile.h"

#include <cmath>

#include "app/core/hash32.h"

namespace cb {
namespace {

constexpr float kNeck = 0.33f;  // a neck narrows by this fraction of what a lobe swells

// The lattice value at integer position i of stroke `seed`'s noise in [-1, 1]: lobes and necks
// alternate (a cumulus outline is bulges between waists), each of a seeded strength in
// [0.5, 1], from a seeded phase, so even a short stroke has a lobe and a neck.
float latticeValue(uint32_t seed, int64_t i) {
  const uint32_t base = hashU32(seed * 0x9e3779b9u + 0x2545f491u);
  const uint32_t h = hashU32(base ^ uint32_t(i));
  const float strength = 0.5f + 0.5f * float(h >> 8) * (1.0f / 16777216.0f);
  return ((uint64_t(i) + (base >> 31)) & 1u) != 0u ? -strength : strength;
}

}  // namespace

float billowFactor(uint32_t stroke_index, float arc_px, float feature_px, float amplitude) {
  if (amplitude == 0.0f || !(feature_px > 0.0f)) return 1.0f;
  const float x = arc_px / feature_px;
  const float cell = std::floor(x);
  const float f = x - cell;
  const float s = f * f * (3.0f - 2.0f * f);  // smoothstep: no corners in the outline
  const int64_t i = int64_t(cell);
  const float v = latticeValue(stroke_index, i) +
                  (latticeValue(stroke_index, i + 1) - latticeValue(stroke_index, i)) * s;
  // Lobes swell by up to A, necks narrow by up to kNeck · A: a cumulus outline is round bulges on
  // shallow waists, and a neck as deep as a lobe would thin a light stroke into gaps.
  return 1.0f + amplitude * (v >= 0.0f ? v : kNeck * v);
}

}  // namespace cb
