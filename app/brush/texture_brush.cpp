#include "app/brush/texture_brush.h"

#include "app/brush/billow_profile.h"

namespace cb {

TextureBrush::TextureBrush(const StrokeParams& stroke, const DispersionParams& dispersion,
                           float nominal_diameter_px)
    : dispersion_(dispersion),
      billow_(stroke.billow),
      billow_feature_px_(stroke.billow_length * nominal_diameter_px),
      resampler_(stroke.spacing_px, dispersion.speed_smoothing_ms) {}

FootprintRect TextureBrush::beginStroke(uint32_t stroke_index, const StrokePoint& first,
                                        Footprint* fp) {
  field_.reset(stroke_index, dispersion_.noise_scale_px);
  stroke_index_ = stroke_index;
  dabs_.clear();
  resampler_.begin(first, &dabs_);
  return stampAll(fp);
}

void TextureBrush::prepareStroke(uint32_t stroke_index) {
  field_.reset(stroke_index, dispersion_.noise_scale_px);
}

FootprintRect TextureBrush::continueStroke(const StrokePoint& point, Footprint* fp) {
  dabs_.clear();
  resampler_.add(point, &dabs_);
  return stampAll(fp);
}

FootprintRect TextureBrush::stampAll(Footprint* fp) {
  FootprintRect changed;
  for (Dab& dab : dabs_) {
    dab.size_factor = billowFactor(stroke_index_, dab.arc_px, billow_feature_px_, billow_);
    changed = changed.united(stampDab(dab, dispersionForSpeed(dispersion_, dab.speed_px_s), fp));
  }
  dab_count_ += dabs_.size();
  return changed;
}

}  // namespace cb
