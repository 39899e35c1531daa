// The 3D brush (thesis §5.3.1, Fig. 5.7): each dab splats a slice of the 64³ ink volume cut by
// a plane that the pen's pressure and tilt set. Light pressure gives sparse noise, hard pressure
// a solid body, a tilted pen the asymmetric split tip.
//
// Samples are computed at quantised pressure and tilt and cached by that key, so a pen whose
// pressure and tilt change little reuses the last slices, and a cached sample is bit-identical
// to a fresh one (the cache can never change a footprint).
#pragma once

#include <cstdint>
#include <memory>
#include <unordered_map>

#include "app/brush/brush_sample.h"
#include "app/brush/ink_volume.h"
#include "app/brush/texture_brush.h"

namespace cb {

class Brush3D : public TextureBrush {
 public:
  // `ink` may be shared between brushes (it takes ~50 ms to build); null builds one.
  Brush3D(const BrushConfig& config, std::shared_ptr<const InkVolume> ink = nullptr);
  BrushKind kind() const override { return BrushKind::k3D; }
  float reachPx() const override { return 0.5f * billowedDiameter(params_.diameter_px) + 1.0f; }

  // The sample for a pen state (through the cache unless caching is off).
  const BrushSample& sampleFor(float pressure, float tilt_x_deg, float tilt_y_deg);
  // Off: every dab ray-marches its slice again (the benchmark's naive baseline).
  void setCaching(bool on) { caching_ = on; }
  uint64_t cacheHits() const { return hits_; }
  uint64_t cacheMisses() const { return misses_; }
  const InkVolume& ink() const { return *ink_; }

 protected:
  FootprintRect stampDab(const Dab& dab, float dispersion, Footprint* footprint) override;

 private:
  Brush3DParams params_;
  std::shared_ptr<const InkVolume> ink_;
  std::unordered_map<uint64_t, BrushSample> cache_;
  BrushSample scratch_;
  bool caching_ = true;
  uint64_t hits_ = 0, misses_ = 0;
};

}  // namespace cb
