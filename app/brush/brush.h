// The brush interface: a stroke of pen points in, an uncleared float footprint out (thesis ch. 5).
// Every call returns the footprint rectangle it changed, so the live overlay uploads only that.
#pragma once

#include <cstdint>
#include <memory>

#include "app/brush/brush_config.h"
#include "app/brush/footprint_rect.h"
#include "app/brush/stroke_result.h"

namespace cb {

class Brush {
 public:
  virtual ~Brush() = default;
  virtual BrushKind kind() const = 0;
  // Tip-down. All randomness of the stroke is seeded from `stroke_index`.
  virtual FootprintRect beginStroke(uint32_t stroke_index, const StrokePoint& first,
                                    Footprint* footprint) = 0;
  virtual FootprintRect continueStroke(const StrokePoint& point, Footprint* footprint) = 0;
  // Optional: precompute what stroke `stroke_index` will need (its noise pattern), so tip-down
  // does not pay for it. The engine calls this at tip-up for the next stroke.
  virtual void prepareStroke(uint32_t /*stroke_index*/) {}
  // Tip-up; a brush with internal dynamics may still settle its last marks here.
  virtual FootprintRect endStroke(Footprint* /*footprint*/) { return {}; }
  // How far from the pen tip this brush can leave ink, in footprint pixels.
  virtual float reachPx() const = 0;
};

std::unique_ptr<Brush> makeBrush(BrushKind kind, const BrushConfig& config);

}  // namespace cb
