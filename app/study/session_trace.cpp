#include "app/study/session_trace.h"

#include <cstring>
#include <filesystem>
#include <limits>

namespace cb {

int64_t elapsedNs(int64_t t, int64_t origin) {
  int64_t d = 0;
  if (!__builtin_sub_overflow(t, origin, &d)) return d;
  return t > origin ? std::numeric_limits<int64_t>::max() : std::numeric_limits<int64_t>::min();
}

SessionTrace sessionTraceFromJournal(const JournalReadResult& journal, const std::string& path,
                                     const std::string& id) {
  SessionTrace trace;
  trace.id = id;
  trace.path = path;
  trace.journal_warning = journal.error;
  if (!journal.records.empty()) trace.t0_ns = journal.records.front().t_ns;
  for (size_t i = 0; i < journal.records.size(); ++i) {
    const JournalRecord& record = journal.records[i];
    switch (record.type) {
      case JournalRecordType::kPenSample: {
        std::optional<PenSample> sample = decodePenSample(record.payload);
        if (!sample)
          throw StudyInputError(
              path + ": record " + std::to_string(i) + " (pen sample): payload of " +
              std::to_string(record.payload.size()) + " bytes is not a pen sample");
        trace.samples.push_back(*sample);
        trace.sample_records.push_back(i);
        break;
      }
      case JournalRecordType::kDevice: {
        std::optional<PenDeviceInfo> device = decodeDeviceInfo(record.payload);
        if (!device)
          throw StudyInputError(path + ": record " + std::to_string(i) + " (device): payload of " +
                                std::to_string(record.payload.size()) +
                                " bytes is not a device description");
        if (!trace.device) trace.device = *device;
        // The name may fill its buffer without a terminator.
        const size_t n = strnlen(device->name, sizeof device->name);
        trace.events.push_back({i, record.type, record.t_ns, std::string(device->name, n)});
        break;
      }
      case JournalRecordType::kFrame:
        // Frame timing (journal_frame.h): kept apart from the events, binary and one a frame.
        if (std::optional<FrameRecord> frame = decodeFrameRecord(record.t_ns, record.payload))
          trace.frames.push_back(*frame);
        break;
      default:
        trace.events.push_back({i, record.type, record.t_ns, std::string(record.text())});
        break;
    }
  }
  return trace;
}

SessionTrace loadSessionTrace(const std::string& path) {
  JournalReadResult journal = readJournal(path);
  if (journal.records.empty())
    throw StudyInputError(path + ": no journal records" +
                          (journal.error.empty() ? std::string() : " (" + journal.error + ")"));
  return sessionTraceFromJournal(journal, path, std::filesystem::path(path).stem().string());
}

}  // namespace cb
