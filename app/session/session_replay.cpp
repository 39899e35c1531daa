#include "app/session/session_replay.h"

#include <cstring>

namespace cb {

SessionReplay replaySession(const JournalReadResult& journal, const BrushConfig& brush,
                            const MappingConfig& mapping,
                            const PaintSessionSettings& settings_fallback) {
  SessionReplay replay;
  replay.journal_error = journal.error;
  PaintSessionSettings settings = settings_fallback;
  for (size_t i = 0; i < journal.records.size(); ++i) {
    const JournalRecord& record = journal.records[i];
    if (record.type == JournalRecordType::kPenSample) break;
    if (record.type == JournalRecordType::kSession) {
      std::string error;
      if (!parseSessionSettings(record.text(), &settings, &error))
        replay.problems.push_back("record " + std::to_string(i) + ": " + error);
      break;
    }
  }
  replay.session = std::make_unique<PaintSession>(settings, brush, mapping);
  replay.session->setQuietMapping(true);
  for (size_t i = 0; i < journal.records.size(); ++i) {
    const JournalRecord& record = journal.records[i];
    std::string error;
    if (!replay.session->applyRecord(record, nullptr, &error)) {
      replay.problems.push_back("record " + std::to_string(i) + " (t " +
                                std::to_string(record.t_ns) + " ns): " + error);
      continue;
    }
    ++replay.records_applied;
    if (record.type == JournalRecordType::kPenSample) ++replay.pen_samples;
  }
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
  const size_t count = size_t(dims.x) * size_t(dims.y) * size_t(dims.z);
  mix(volume.data(), count * sizeof(float));
  return hash;
}

}  // namespace cb
