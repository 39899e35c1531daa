// What a painter screen test draws with and records: the test display (EGL surfaceless), a
// renderer on it, and a PaintSession (quiet mapping) journalling to a file, as `cloudbrush paint`
// wires them. The test reads the journal back to replay it.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "app/brush/brush_config.h"
#include "app/mapping/mapping_config.h"
#include "app/render/gl/display.h"
#include "app/render/volume_renderer.h"
#include "app/session/paint_session.h"
#include "drivers/core/journal.h"

namespace cb::test {

struct RecordedPainter {
  // The display at the settings' screen size, the renderer, and the session journalling to
  // `journal_path` from `start_ns`. False with *error when one of them cannot be opened.
  bool open(const PaintSessionSettings& settings, const BrushConfig& brush,
            const MappingConfig& mapping, const std::string& journal_path, int64_t start_ns,
            std::string* error);

  std::unique_ptr<Display> display;
  VolumeRenderer renderer;
  std::unique_ptr<PaintSession> session;
  JournalWriter journal;
  std::string recorded;  // the journal's path
};

}  // namespace cb::test
