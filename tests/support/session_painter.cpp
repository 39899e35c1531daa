#include "tests/support/session_painter.h"

#include <string>

#include <gtest/gtest.h>

namespace cb::test {

SessionPainter::SessionPainter(const PaintSessionSettings& settings, const BrushConfig& brush,
                               const MappingConfig& mapping)
    : tablet(syntheticTablet(settings.screen_width, settings.screen_height)),
      session(settings, brush, mapping) {
  session.setQuietMapping(true);
  session.setDevice(tablet, 0);
}

void SessionPainter::stroke(const SyntheticStroke& s) {
  const PaintSessionSettings& settings = session.settings();
  for (const PenSample& sample :
       syntheticPenSamples(s, tablet, settings.screen_width, settings.screen_height, 200.0, t)) {
    session.feed(sample);
    t = sample.t_ns;
  }
  t += 100'000'000;
}

void SessionPainter::apply(const UiChange& change) {
  std::string error;
  ASSERT_TRUE(session.apply(change, t, &error)) << error;
}

}  // namespace cb::test
