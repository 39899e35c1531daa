#include "tests/support/reference_journal.h"

#include <cstdint>

#include "app/session/paint_session.h"
#include "app/session/synthetic_session.h"
#include "drivers/core/journal.h"

namespace cb::test {

bool recordReferenceJournal(const std::string& path, int width, int height, int rounds,
                            std::string* error) {
  PaintSession recorder({width, height, 16}, BrushConfig{}, MappingConfig{});
  recorder.setQuietMapping(true);
  JournalWriter journal;
  if (!journal.open(path)) return *error = journal.error(), false;
  recorder.recordTo(&journal, 0);
  const PenDeviceInfo tablet = syntheticTablet(width, height);
  recorder.setDevice(tablet, 0);
  int64_t t = 1'000'000'000;
  for (int round = 0; round < rounds; ++round)
    for (const SyntheticStroke& stroke : referencePaintStrokes(width, height)) {
      for (const PenSample& s : syntheticPenSamples(stroke, tablet, width, height, 200.0, t)) {
        recorder.feed(s);
        t = s.t_ns;
      }
      t += 300'000'000;
    }
  return true;
}

}  // namespace cb::test
