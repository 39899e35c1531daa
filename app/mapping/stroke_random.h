// Deterministic randomness for the mapping: a SplitMix64 stream keyed by (stroke index, item),
// so every pixel's scatter depends only on the stroke and the pixel, never on thread timing.
#pragma once

#include <cstdint>

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
  // Approximately standard normal: the Irwin–Hall sum of four uniforms (the four 16-bit parts
  // of one draw), centred and scaled to unit variance. Bounded at ±2√3 ≈ ±3.46; no
  // transcendental functions, so scattering hundreds of thousands of samples stays cheap.
  float gaussian() {
    const uint64_t r = next();
    const uint32_t sum = uint32_t(r & 0xFFFF) + uint32_t((r >> 16) & 0xFFFF) +
                         uint32_t((r >> 32) & 0xFFFF) + uint32_t(r >> 48);
    // Each part is uniform on [0, 65535]: mean 2·65535, variance 4·(65536² − 1)/12.
    constexpr float kMean = 2.0f * 65535.0f;
    constexpr float kInvStd = 1.7320508f / 65536.0f;  // 1 / sqrt(4 · 65536² / 12)
    return (float(sum) - kMean) * kInvStd;
  }

 private:
  uint64_t state_;
};

}  // namespace cb
