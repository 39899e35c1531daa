// Replaying a session journal headlessly (DESIGN.md "One data flow"): the records are applied in
// order to a fresh PaintSession made from the journal's Session record, so raw samples pass
// through the calibration that was in force at that moment (the journal's Calibration records,
// never the local config). Brush and mapping parameters come from the journal's Settings records
// (the configuration in force while painting), so a journal replays the same with any local
// config; journals from before those records take them from the caller (config/brush.toml,
// config/mapping.toml), as they always did. A corrupt or torn journal replays its intact prefix;
// the problem is reported with the reader's byte offset.
#pragma once

#include <functional>
#include <memory>
#include <optional>
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
  bool recorded_settings = false;  // brush and mapping came from the journal, not the caller
  std::optional<MappedSample> last_mapped;  // the last pen sample as the session mapped it
  std::string journal_error;                // the reader's message (file, byte offset) or empty
  std::vector<std::string> problems;        // records that could not be applied ("record N: ...")
  bool complete() const { return journal_error.empty() && problems.empty(); }
};

// The session settings, brush and mapping a journal was recorded with: its Session and Settings
// records before the first pen sample; the fallbacks where it has none. Records that do not
// parse are named in `problems` ("record N: ...") and leave the fallback in place.
struct RecordedSettings {
  PaintSessionSettings settings;
  BrushConfig brush;
  MappingConfig mapping;
  bool recorded_brush_or_mapping = false;  // a Settings record gave the brush or the mapping
  std::vector<std::string> problems;
};
RecordedSettings recordedSettings(const std::vector<JournalRecord>& records,
                                  const BrushConfig& brush, const MappingConfig& mapping,
                                  const PaintSessionSettings& settings_fallback = {});

// What a caller sees of a replay as it runs (`cloudbrush replay --frames` draws the screens from
// it). The session is the replay's own: a hook reads it and changes nothing in it.
struct ReplayHooks {
  // Before each record is applied, with its index, and with journal.records.size() at the end,
  // while the session shows the state up to there.
  std::function<void(size_t index, PaintSession& session)> before_record;
  // After record `index` was applied; `sample` is a pen sample's outcome, else null.
  std::function<void(size_t index, const SampleOutcome* sample)> after_record;
};

// `settings_fallback` is used when the journal has no Session record before its first sample;
// `brush` and mapping when it has no Settings records.
SessionReplay replaySession(const JournalReadResult& journal, const BrushConfig& brush,
                            const MappingConfig& mapping,
                            const PaintSessionSettings& settings_fallback = {},
                            const ReplayHooks& hooks = {});

// FNV-1a 64 over the volume's dims and raw float bytes: equal sums mean equal volumes.
uint64_t volumeChecksum(const Volume& volume);

}  // namespace cb
