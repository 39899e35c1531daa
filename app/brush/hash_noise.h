// Deterministic noise for the brushes: an integer hash of lattice coordinates and a seed, value
// noise with smooth interpolation, and fractal sums of it. No global state and no std::rand, so
// the same seed gives the same bits on every machine and thread count.
#pragma once

#include <cstdint>

#include "app/core/hash32.h"

namespace cb {

uint32_t hashCombine(uint32_t seed, int32_t a, int32_t b = 0, int32_t c = 0);
// Uniform in [0, 1) from a hash.
inline float unitFloat(uint32_t h) {
  return float(h >> 8) * (1.0f / 16777216.0f);
}

// Value noise in [0, 1]. `period` > 0 wraps the lattice (a tileable pattern).
float valueNoise2D(float x, float y, uint32_t seed, int period = 0);
float valueNoise3D(float x, float y, float z, uint32_t seed);
// Sum of `octaves` octaves (frequency ×2, amplitude ×½), normalised back into [0, 1].
float fractalNoise2D(float x, float y, int octaves, uint32_t seed, int period = 0);
float fractalNoise3D(float x, float y, float z, int octaves, uint32_t seed);

// A small deterministic generator for brush construction (bristle layout etc.).
class SeededRandom {
 public:
  explicit SeededRandom(uint32_t seed) : state_(hashU32(seed ^ 0x9e3779b9u)) {}
  uint32_t next() { return state_ = hashU32(state_ + 0x6d2b79f5u); }
  float uniform() { return unitFloat(next()); }
  float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }

 private:
  uint32_t state_;
};

}  // namespace cb
