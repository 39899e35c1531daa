// Replaying a session journal headlessly (DESIGN.md "One data flow"): the records are applied in
// order to a fresh PaintSession made from the journal's Session record, so raw samples pass
// through the calibration that was in force at that moment (the journal's Calibration records,
// never the local config). Brush and mapping parameters come from the caller (config/brush.toml,
// config/mapping.toml). A corrupt or torn journal replays its intact prefix; the problem is
// reported with the reader's byte offset.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "app/session/paint_session.h"
#include "drivers/core/journal.h"

namespace cb {

struct SessionReplay {
  std::unique_ptr<PaintSession> session;  // null when nothing could be replayed
  size_t records_applied = 0;
  size_t pen_samples = 0;
  uint32_t strokes_mapped = 0;
  std::string journal_error;          // the reader's message (file, byte offset) or empty
  std::vector<std::string> problems;  // records that could not be applied ("record N: ...")
  bool complete() const { return journal_error.empty() && problems.empty(); }
};

// `settings_fallback` is used when the journal has no Session record before its first sample.
SessionReplay replaySession(const JournalReadResult& journal, const BrushConfig& brush,
                            const MappingConfig& mapping,
                            const PaintSessionSettings& settings_fallback = {});

// FNV-1a 64 over the volume's dims and raw float bytes: equal sums mean equal volumes.
uint64_t volumeChecksum(const Volume& volume);

}  // namespace cb
