// Speed -> ink dispersion (thesis §5.1.2, mechanism 3 "speed management"; §5.3.2 "a dispersed
// ink effect related to brush velocity"): slow strokes lay ink solid, fast strokes leave a
// sparser, wispier trace. The pattern is fixed in footprint space for the whole stroke (seeded
// from the stroke index), so overlapping dabs agree on which pixels stay dry and the result does
// not depend on how densely the pen was sampled.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "app/brush/brush_config.h"

namespace cb {

// 0 at or below slow_speed, max_dispersion at or above fast_speed, smooth in between.
float dispersionForSpeed(const DispersionParams& params, float speed_px_s);

class DispersionField {
 public:
  static constexpr int kTile = 128;  // footprint pixels; the pattern repeats beyond this

  void reset(uint32_t stroke_index, float noise_scale_px);
  // Fraction of ink kept at footprint pixel (x, y) for a dispersion d in 0..1; exactly 1 at d=0.
  float keep(int x, int y, float dispersion) const;

 private:
  // kTile², values 0..1; made once per process for each (stroke index, scale) and shared by the
  // brushes of every session (a new session prepares stroke 0 before any pen comes), the last
  // few kept.
  std::shared_ptr<const std::vector<float>> noise_;
  uint32_t stroke_index_ = 0;
  float scale_ = 0.0f;
};

}  // namespace cb
