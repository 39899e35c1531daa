#include "app/brush/brush_3d.h"

#include <cmath>

#include "app/brush/sample_splat.h"
#include "app/brush/slice_sampler.h"

namespace cb {

Brush3D::Brush3D(const BrushConfig& c, std::shared_ptr<const InkVolume> ink)
    : TextureBrush(c.stroke, c.dispersion, c.brush3d.diameter_px),
      params_(c.brush3d),
      ink_(std::move(ink)) {
  if (!ink_) ink_ = InkVolume::shared(params_.ink_volume_size, params_.ink_seed);
}

const BrushSample& Brush3D::sampleFor(float pressure, float tilt_x_deg, float tilt_y_deg) {
  int qp = int(std::lround(pressure / params_.pressure_quantum));
  int qx = int(std::lround(tilt_x_deg / params_.tilt_quantum_deg));
  int qy = int(std::lround(tilt_y_deg / params_.tilt_quantum_deg));
  uint64_t key = (uint64_t(uint16_t(qp)) << 32) | (uint64_t(uint16_t(qx)) << 16) | uint16_t(qy);
  auto compute = [&] {
    CuttingPlane plane =
        cuttingPlane(*ink_, qp * params_.pressure_quantum, qx * params_.tilt_quantum_deg,
                     qy * params_.tilt_quantum_deg, params_.max_tilt_deg);
    return marchSlab(*ink_, plane, params_);
  };
  if (!caching_ || params_.cache_entries == 0) {
    ++misses_;
    scratch_ = compute();
    return scratch_;
  }
  auto it = cache_.find(key);
  if (it != cache_.end()) {
    ++hits_;
    return it->second;
  }
  ++misses_;
  if (cache_.size() >= size_t(params_.cache_entries)) cache_.clear();
  return cache_.emplace(key, compute()).first->second;
}

FootprintRect Brush3D::stampDab(const Dab& dab, float dispersion, Footprint* fp) {
  const BrushSample& sample = sampleFor(dab.pressure, dab.tilt_x_deg, dab.tilt_y_deg);
  SplatParams splat;
  splat.centre_px = dab.footprint_px;
  splat.diameter_px = params_.diameter_px * dab.size_factor;  // the edge billows
  splat.dispersion = dispersion;
  return splatSample(sample, splat, dispersionField(), fp);
}

}  // namespace cb
