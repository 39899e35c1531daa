#include "app/session/gallery_painting.h"

#include <chrono>

#include "app/brush/stroke_engine.h"
#include "app/session/paint_session.h"
#include "app/volume/sky_extent.h"

namespace cb {

GalleryCloud paintGalleryStroke(const GalleryStroke& g, BrushKind kind, const BrushConfig& brush,
                                StrokeMapper& mapper, int w, int h, uint32_t index) {
  PaintSessionSettings settings;
  settings.screen_width = w;
  settings.screen_height = h;
  settings.grid = 256;  // the painter's (app/cli/command_paint.cpp --grid)
  GalleryCloud cloud;
  cloud.camera = initialPaintCamera(settings);
  cloud.volume = makeSkyVolume(settings.skyExtent());
  StrokeEngine engine(brush, w, h);
  engine.setBrushSize(brush.stroke.size);
  engine.selectBrush(kind);
  engine.setPaintView(PaintView{cloud.camera}, cloud.canvas);
  engine.setNextStrokeIndex(index);
  engine.prepareNextStroke();
  const glm::vec2 scale(float(engine.footprintWidth()) / float(w),
                        float(engine.footprintHeight()) / float(h));
  const std::vector<BrushInput> samples = scaledSamples(g.samples, scale);
  engine.beginStroke(samples.front());
  for (size_t i = 1; i < samples.size(); ++i) engine.addSample(samples[i]);
  const StrokeResult stroke = engine.endStroke();
  const auto t0 = std::chrono::steady_clock::now();
  cloud.report = mapper.map(stroke, cloud.volume);
  cloud.mapping_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return cloud;
}

}  // namespace cb
