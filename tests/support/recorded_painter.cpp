#include "tests/support/recorded_painter.h"

#include "tests/support/test_display.h"

namespace cb::test {

bool RecordedPainter::open(const PaintSessionSettings& settings, const BrushConfig& brush,
                           const MappingConfig& mapping, const std::string& journal_path,
                           int64_t start_ns, std::string* error) {
  display = openTestDisplay(settings.screen_width, settings.screen_height, error);
  if (!display || !renderer.init(error)) return false;
  session = std::make_unique<PaintSession>(settings, brush, mapping);
  session->setQuietMapping(true);
  recorded = journal_path;
  if (!journal.open(recorded)) {
    *error = recorded + ": " + journal.error();
    return false;
  }
  session->recordTo(&journal, start_ns);
  return true;
}

}  // namespace cb::test
