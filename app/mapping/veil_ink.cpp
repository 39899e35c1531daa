#include "app/mapping/veil_ink.h"

#include "app/scene/drawable_region.h"

namespace cb {

long long leaveOutVeiledInk(StrokeResult* stroke, glm::vec3 sky_min, glm::vec3 sky_max,
                            float empty_threshold) {
  Footprint& f = stroke->footprint;
  if (f.width <= 0 || f.height <= 0 || f.values.size() != size_t(f.width) * size_t(f.height))
    return 0;  // the mapper reports a malformed footprint
  const DrawableRegion region(stroke->view.camera, stroke->canvas, sky_min, sky_max, f.width,
                              f.height);
  long long cleared = 0;
  for (int y = 0; y < f.height; ++y) {
    // The region is convex: each row lands on one run [x0, x1], or nowhere.
    int x0 = f.width, x1 = -1;
    if (!region.rowSpan(y, &x0, &x1)) x0 = f.width, x1 = -1;
    float* row = &f.values[size_t(y) * size_t(f.width)];
    for (int x = 0; x < f.width; ++x) {
      if (x >= x0 && x <= x1) continue;
      // NaN is empty and +inf ink, as the mapper reads them (stroke_mapper.cpp).
      if (row[x] > empty_threshold) {
        row[x] = 0.0f;
        ++cleared;
      }
    }
  }
  return cleared;
}

}  // namespace cb
