// A PaintSession painted through its real input path: synthetic strokes
// (app/session/synthetic_session.h) sampled at 200 Hz on a synthetic tablet the size of the
// session's screen, fed sample by sample, with 100 ms between strokes. For session tests that
// paint, switch modes and apply UI changes without a display.
#pragma once

#include <cstdint>

#include "app/brush/brush_config.h"
#include "app/mapping/mapping_config.h"
#include "app/session/paint_session.h"
#include "app/session/synthetic_session.h"
#include "app/session/ui_change.h"

namespace cb::test {

struct SessionPainter {
  SessionPainter(const PaintSessionSettings& settings, const BrushConfig& brush,
                 const MappingConfig& mapping);
  // Feeds the stroke's samples (the session maps it at pen-up), then moves the clock on 100 ms.
  void stroke(const SyntheticStroke& s);
  // Applies a UI change at the current time; a refused change fails the test (gtest).
  void apply(const UiChange& change);

  PenDeviceInfo tablet;
  PaintSession session;
  int64_t t = 1'000'000'000;
};

}  // namespace cb::test
