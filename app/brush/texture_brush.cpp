#include "app/brush/texture_brush.h"

namespace cb {

TextureBrush::TextureBrush(const StrokeParams& stroke, const DispersionParams& dispersion)
    : dispersion_(dispersion), resampler_(stroke.spacing_px, dispersion.speed_smoothing_ms) {}

FootprintRect TextureBrush::beginStroke(uint32_t stroke_index, const StrokePoint& first,
                                        Footprint* fp) {
  field_.reset(stroke_index, dispersion_.noise_scale_px);
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
  for (const Dab& dab : dabs_)
    changed = changed.united(stampDab(dab, dispersionForSpeed(dispersion_, dab.speed_px_s), fp));
  dab_count_ += dabs_.size();
  return changed;
}

}  // namespace cb
