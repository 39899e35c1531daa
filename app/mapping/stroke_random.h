// Deterministic randomness for the mapping: a SplitMix64 stream keyed by (stroke index, item),
// so every pixel's scatter depends only on the stroke and the pixel, never on thread timing.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

namespace cb {

class StrokeRandom {
 public:
  StrokeRandom(uint32_t stroke_index, uint64_t item)
      : state_((uint64_t(stroke_index) << 40) ^ (item * 0xD1B54A32D192ED03ull) ^ 0x5DEECE66Dull) {}

  uint64_t next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // Uniform in (0, 1).
  double uniform() { return (double(next() >> 11) + 0.5) * (1.0 / 9007199254740992.0); }
  // Standard normal (Box–Muller; one value per call, the second is dropped for simplicity).
  float gaussian() {
    double u1 = uniform(), u2 = uniform();
    return float(std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2));
  }

 private:
  uint64_t state_;
};

}  // namespace cb
