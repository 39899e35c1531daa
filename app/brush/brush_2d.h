// The 2D brush (thesis §5.3.1): a static brush texture splatted along the path like Photoshop's
// brush; its size grows with pressure and tilt has no effect. The texture is a bundle of bristle
// spots, so dragging it leaves the striations along the stroke that the thesis's 2D footprints
// show (Fig. 5.8a).
#pragma once

#include "app/brush/brush_sample.h"
#include "app/brush/texture_brush.h"

namespace cb {

// The static texture: `bristles` soft spots scattered over a disc, seeded by `seed`.
BrushSample makeBristleTexture(const Brush2DParams& params);

class Brush2D : public TextureBrush {
 public:
  Brush2D(const BrushConfig& config);
  BrushKind kind() const override { return BrushKind::k2D; }
  float reachPx() const override { return 0.5f * billowedDiameter(params_.max_diameter_px) + 1.0f; }
  float diameterFor(float pressure) const;
  const BrushSample& texture() const { return texture_; }

 protected:
  FootprintRect stampDab(const Dab& dab, float dispersion, Footprint* footprint) override;

 private:
  Brush2DParams params_;
  BrushSample texture_;
};

}  // namespace cb
