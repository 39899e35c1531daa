// A journal's recorded settings (Settings records, drivers/core/JOURNAL.md) read back as the
// brush and mapping that painted it. The one place that knows what a key the recorded text lacks
// stands for: the value that reproduces the version that wrote the text, which may differ from
// today's default (a local brush.toml / mapping.toml lacking a key gets the default instead).
//
//   key the text lacks                    value     what it reproduces (versions up to 9e22266)
//   spheres.outline_chord_voxels          0         spheres filled to r / (1 − erosion/2)
//   edges.tangent_at_sphere_depth         false     P_t at the ray's closest point to P_S
//   spheres.billow_amplitude              0         spheres at their circles' radii (no billows)
//   spheres.puff_probability              0         no edge puffs
//   stroke.auto_end_light_by_hysteresis   false     "light touch" = calibrated pressure < 5%
//   stroke.size                           1         footprint at the screen's resolution (a
//                                                   journal with no brush.toml at all: also 1)
//   stroke.billow                         0         dabs of one diameter along the stroke (no
//                                                   billowing edge; also with no brush.toml)
//   skeleton.stamp_spacing_px             0         bristles stamped once per Verlet step
//   skeleton.end_settle_steps             0         the skeleton stops at the pen's lift
//
// A new key that changes what a journal paints gets its row here, in the same commit.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "app/brush/brush_config.h"
#include "app/mapping/mapping_config.h"

namespace cb {

// Today's defaults, with the rows above for keys a recorded text lacks.
BrushConfig recordedBrushAbsentValues();
MappingConfig recordedMappingAbsentValues();

// The brush of a journal that recorded none (specification 1.0): the replaying machine's
// `local` one, with the keys that came after such journals (stroke.size, stroke.billow,
// skeleton.stamp_spacing_px, skeleton.end_settle_steps) at their absent values above.
BrushConfig unrecordedBrush(const BrushConfig& local);

// A recorded brush.toml text; false with "NAME:LINE:COL: what" in *errors if it is malformed
// (fields that were bad keep their absent values).
bool parseRecordedBrush(std::string_view text, const std::string& name, BrushConfig* out,
                        std::vector<std::string>* errors);
// A recorded mapping.toml text; throws like parseMappingConfigText.
MappingConfig parseRecordedMapping(std::string_view text, const std::string& name);

}  // namespace cb
