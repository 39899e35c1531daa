#include "app/session/session_replay.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "app/session/recorded_settings.h"
#include "drivers/core/journal_records.h"

namespace cb {

RecordedSettings recordedSettings(const std::vector<JournalRecord>& records,
                                  const BrushConfig& brush, const MappingConfig& mapping,
                                  const PaintSessionSettings& settings_fallback) {
  RecordedSettings recorded{settings_fallback, brush, mapping, false, {}};
  bool have_session = false, have_brush = false;
  for (size_t i = 0; i < records.size(); ++i) {
    const JournalRecord& record = records[i];
    if (record.type == JournalRecordType::kPenSample) break;
    std::string error;
    if (record.type == JournalRecordType::kSession && !have_session) {
      have_session = true;
      if (!parseSessionSettings(record.text(), &recorded.settings, &error))
        recorded.problems.push_back("record " + std::to_string(i) + ": " + error);
    } else if (record.type == JournalRecordType::kSettings) {
      // The brush and mapping in force while painting (journals from before Settings records
      // replay with the caller's, as they always did).
      std::string name, body;
      std::vector<std::string> errors;
      if (!parseSettingsRecord(record.text(), &name, &body, &error)) {
        recorded.problems.push_back("record " + std::to_string(i) + ": " + error);
      } else if (name == "brush.toml") {
        if (!parseRecordedBrush(body, "record " + std::to_string(i) + " (brush.toml)",
                                &recorded.brush, &errors))
          for (const std::string& e : errors) recorded.problems.push_back(e);
        recorded.recorded_brush_or_mapping = have_brush = true;
      } else if (name == "mapping.toml") {
        try {
          recorded.mapping =
              parseRecordedMapping(body, "record " + std::to_string(i) + " (mapping.toml)");
        } catch (const std::exception& e) {
          recorded.problems.push_back(e.what());
        }
        recorded.recorded_brush_or_mapping = true;
      }
    }
  }
  // A journal without a recorded brush.toml predates the brush size and the skeleton brush's
  // stamp spacing, whatever the replaying machine's brush.toml says (recorded_settings.h).
  if (!have_brush) recorded.brush = unrecordedBrush(recorded.brush);
  return recorded;
}

SessionReplay replaySession(const JournalReadResult& journal, const BrushConfig& brush,
                            const MappingConfig& mapping,
                            const PaintSessionSettings& settings_fallback,
                            const ReplayHooks& hooks) {
  SessionReplay replay;
  replay.journal_error = journal.error;
  RecordedSettings recorded = recordedSettings(journal.records, brush, mapping, settings_fallback);
  replay.recorded_settings = recorded.recorded_brush_or_mapping;
  replay.problems = std::move(recorded.problems);
  replay.session =
      std::make_unique<PaintSession>(recorded.settings, recorded.brush, recorded.mapping);
  replay.session->setQuietMapping(true);
  for (size_t i = 0; i < journal.records.size(); ++i) {
    const JournalRecord& record = journal.records[i];
    if (hooks.before_record) hooks.before_record(i, *replay.session);
    std::string error;
    SampleOutcome outcome;
    const bool sample = record.type == JournalRecordType::kPenSample;
    if (!replay.session->applyRecord(record, sample ? &outcome : nullptr, &error)) {
      replay.problems.push_back("record " + std::to_string(i) + " (t " +
                                std::to_string(record.t_ns) + " ns): " + error);
      continue;
    }
    ++replay.records_applied;
    if (sample) {
      ++replay.pen_samples;
      replay.last_mapped = outcome.mapped;
    }
    if (hooks.after_record) hooks.after_record(i, sample ? &outcome : nullptr);
  }
  if (hooks.before_record) hooks.before_record(journal.records.size(), *replay.session);
  replay.strokes_mapped = replay.session->strokesMapped();
  return replay;
}

uint64_t volumeChecksum(const Volume& volume) {
  uint64_t hash = 1469598103934665603ull;
  const auto mix = [&](const void* data, size_t n) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) {
      hash ^= bytes[i];
      hash *= 1099511628211ull;
    }
  };
  const glm::ivec3 dims = volume.dims();
  mix(&dims, sizeof dims);
  // The voxels' bytes in the dense order (x fastest), as the dense grid held them. FNV-1a turns
  // a zero byte into one multiplication by its prime, so a run of n zero bytes (the unallocated
  // bricks of a sparse sky) is one multiplication by prime^n: the same hash without reading them.
  uint64_t zero_bytes = 0;
  const auto flushZeros = [&] {
    uint64_t factor = 1, base = 1099511628211ull;
    for (uint64_t n = zero_bytes; n; n >>= 1, base *= base)
      if (n & 1) factor *= base;
    hash *= factor;
    zero_bytes = 0;
  };
  const int b = Volume::kBrickSize;
  std::vector<float> segment(static_cast<size_t>(b));
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; x += b) {
        const int n = std::min(b, dims.x - x);
        if (!volume.brick(glm::ivec3(x, y, z) / b)) {
          zero_bytes += uint64_t(n) * sizeof(float);
          continue;
        }
        flushZeros();
        volume.readLine({x, y, z}, 0, n, segment.data());
        mix(segment.data(), size_t(n) * sizeof(float));
      }
  flushZeros();
  return hash;
}

}  // namespace cb
