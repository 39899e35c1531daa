// One stroke of the stroke gallery (app/brush/stroke_gallery.h) painted as the painter paints
// it at its defaults: the screen's starting paint view (format 2, initialPaintCamera), the
// default canvas and sky (grid 256, kDefaultSkySpan), the given brush at its configured size
// through the real StrokeEngine, mapped by the given StrokeMapper into a fresh sky. For the
// gallery test, its goldens and `cloudbrush bench strokes`.
#pragma once

#include <cstdint>

#include "app/brush/brush_config.h"
#include "app/brush/stroke_gallery.h"
#include "app/mapping/stroke_mapper.h"
#include "app/volume/volume.h"

namespace cb {

struct GalleryCloud {
  Camera camera = Camera::reference();  // the paint view
  Canvas canvas;
  Volume volume;
  MappingReport report;
  double mapping_ms = 0;
};

GalleryCloud paintGalleryStroke(const GalleryStroke& stroke, BrushKind brush_kind,
                                const BrushConfig& brush, StrokeMapper& mapper, int screen_width,
                                int screen_height, uint32_t stroke_index);

}  // namespace cb
