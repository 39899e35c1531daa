// Common part of the two texture-based brushes (thesis §5.3.1, Fig. 5.6): the path is resampled
// at a fixed arc-length step and a brush sample is splatted at every step; only the sample
// differs between the 2D and the 3D brush.
#pragma once

#include <vector>

#include "app/brush/brush.h"
#include "app/brush/dispersion.h"
#include "app/brush/path_resampler.h"

namespace cb {

class TextureBrush : public Brush {
 public:
  FootprintRect beginStroke(uint32_t stroke_index, const StrokePoint& first,
                            Footprint* footprint) override;
  FootprintRect continueStroke(const StrokePoint& point, Footprint* footprint) override;
  void prepareStroke(uint32_t stroke_index) override;
  uint64_t dabCount() const { return dab_count_; }

 protected:
  // `nominal_diameter_px`: the brush's largest dab, the unit of stroke.billow_length.
  TextureBrush(const StrokeParams& stroke, const DispersionParams& dispersion,
               float nominal_diameter_px);
  // The largest dab diameter a billowing edge reaches, for a nominal one.
  float billowedDiameter(float diameter_px) const { return diameter_px * (1.0f + billow_); }
  // Splats one dab; returns the changed rectangle.
  virtual FootprintRect stampDab(const Dab& dab, float dispersion, Footprint* footprint) = 0;
  const DispersionField& dispersionField() const { return field_; }

 private:
  FootprintRect stampAll(Footprint* footprint);

  DispersionParams dispersion_;
  float billow_, billow_feature_px_;
  uint32_t stroke_index_ = 0;
  PathResampler resampler_;
  DispersionField field_;
  std::vector<Dab> dabs_;
  uint64_t dab_count_ = 0;
};

}  // namespace cb
