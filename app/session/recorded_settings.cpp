#include "app/session/recorded_settings.h"

namespace cb {

BrushConfig recordedBrushAbsentValues() {
  BrushConfig c;
  c.stroke.auto_end_light_by_hysteresis = false;
  return c;
}

MappingConfig recordedMappingAbsentValues() {
  MappingConfig c;
  c.spheres.outline_chord_voxels = 0.0f;
  c.edges.tangent_at_sphere_depth = false;
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
