// The mapping stage as the app uses it: a finished stroke (StrokeResult) becomes voxels in the
// Volume, by the Hybrid Mapping Method (circle growth → sphere mapping → edge mapping, thesis
// §6.3–6.6) or the ray-marching mapping (§6.1). Results merge with max (order-free) and the
// touched box is reported with Volume::markDirty, so the renderer's upload, occupancy and light
// updates pick it up.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "app/brush/stroke_result.h"
#include "app/mapping/circle_growth.h"
#include "app/mapping/edge_mapping.h"
#include "app/mapping/mapping_config.h"
#include "app/mapping/ray_marching_mapping.h"
#include "app/mapping/simplex_noise.h"
#include "app/mapping/sphere_mapping.h"
#include "app/volume/volume.h"

namespace cb {

struct MappingTimings {
  double circle_growth_ms = 0, sphere_mapping_ms = 0, edge_mapping_ms = 0, ray_marching_ms = 0;
  double total_ms = 0;
};

struct MappingReport {
  MappingMethod method = MappingMethod::kHybrid;
  VoxelBox dirty;                     // also passed to Volume::markDirty
  std::vector<Circle> circles;        // HMM: accepted circles (footprint pixels)
  std::vector<MappedSphere> spheres;  // HMM: one per circle
  int growth_steps = 0;
  long long circle_attempts = 0;
  long long non_empty_pixels = 0;
  long long covered_pixels = 0;  // non-empty pixels inside a circle
  EdgeMappingStats edges;
  RayMarchingStats ray_marching;
  MappingTimings timings;
  std::vector<std::string> warnings;  // also logged to stderr, one line each
  // Fraction of the non-empty footprint covered by circles.
  double coveredFraction() const {
    return non_empty_pixels ? double(covered_pixels) / double(non_empty_pixels) : 0.0;
  }
};

class StrokeMapper {
 public:
  // Generates the noise texture (once; §6.5 "only generated when the system is launched").
  explicit StrokeMapper(const MappingConfig& config = {});

  // Maps with the configured method.
  MappingReport map(const StrokeResult& stroke, Volume& volume);
  MappingReport map(const StrokeResult& stroke, Volume& volume, MappingMethod method);

  // Circles of the last HMM stroke, for the overlay (the thesis's "C" key).
  const std::vector<Circle>& lastCircles() const { return last_circles_; }
  const MappingConfig& config() const { return config_; }
  const NoiseTexture& noise() const { return *noise_; }
  // Silences the stderr log lines (warnings stay in the report).
  void setQuiet(bool quiet) { quiet_ = quiet; }
  // Uses growCirclesStraightforward (the benchmark's baseline) instead of growCircles.
  void setStraightforwardCircleGrowth(bool on) { straightforward_growth_ = on; }

 private:
  void warn(MappingReport* report, uint32_t stroke_index, const std::string& text) const;

  MappingConfig config_;
  std::shared_ptr<const NoiseTexture> noise_;  // shared by every mapper (sharedNoiseTexture)
  std::vector<Circle> last_circles_;
  bool quiet_ = false;
  bool straightforward_growth_ = false;
};

}  // namespace cb
