#include "app/session/recorded_settings.h"

namespace cb {

BrushConfig recordedBrushAbsentValues() {
  BrushConfig c;
  c.stroke.auto_end_light_by_hysteresis = false;
  c.stroke.size = 1.0f;
  c.stroke.billow = 0.0f;
  c.skeleton.stamp_spacing_px = 0.0f;
  c.skeleton.end_settle_steps = 0;
  return c;
}

MappingConfig recordedMappingAbsentValues() {
  MappingConfig c;
  c.spheres.outline_chord_voxels = 0.0f;
  c.edges.tangent_at_sphere_depth = false;
  c.spheres.billow_amplitude = 0.0f;
  c.spheres.puff_probability = 0.0f;
  return c;
}

BrushConfig unrecordedBrush(const BrushConfig& local) {
  const BrushConfig absent = recordedBrushAbsentValues();
  BrushConfig c = local;
  c.stroke.size = absent.stroke.size;
  c.stroke.billow = absent.stroke.billow;
  c.skeleton.stamp_spacing_px = absent.skeleton.stamp_spacing_px;
  c.skeleton.end_settle_steps = absent.skeleton.end_settle_steps;
  return c;
}

bool parseRecordedBrush(std::string_view text, const std::string& name, BrushConfig* out,
                        std::vector<std::string>* errors) {
  *out = recordedBrushAbsentValues();
  return parseBrushConfigText(text, name, out, errors);
}

MappingConfig parseRecordedMapping(std::string_view text, const std::string& name) {
  return parseMappingConfigText(text, name, recordedMappingAbsentValues());
}

}  // namespace cb
