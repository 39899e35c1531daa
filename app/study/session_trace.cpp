#include "app/study/session_trace.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <limits>

#include "app/study/study_marker_text.h"

namespace cb {

int64_t elapsedNs(int64_t t, int64_t origin) {
  int64_t d = 0;
  if (!__builtin_sub_overflow(t, origin, &d)) return d;
  return t > origin ? std::numeric_limits<int64_t>::max() : std::numeric_limits<int64_t>::min();
}

namespace {

// The participant (study.info) and the task running (study.stage-begin/-end of stage=task).
void followStudyMarker(const JournalRecord& record, SessionTrace* trace, int* task) {
  const std::string text(record.text());
  if (text.rfind("study.", 0) != 0) return;
  const StudyMarkerFields m = parseStudyMarker(text);
  if (m.event == "study.info" && trace->participant.empty())
    trace->participant = m.get("participant");
  if (m.event == "study.stage-begin" && m.get("stage") == "task" && m.has("task")) {
    const std::string id = m.get("task");
    auto at = std::find(trace->task_ids.begin(), trace->task_ids.end(), id);
    if (at == trace->task_ids.end()) at = trace->task_ids.insert(at, id);
    *task = int(at - trace->task_ids.begin());
  }
  if (m.event == "study.stage-end" || m.event == "study.end") *task = -1;
}

}  // namespace

std::string sessionIdForJournal(const std::string& path) {
  const std::filesystem::path p(path);
  const std::string folder = p.parent_path().filename().string();
  if (p.filename() == "session.cbj" && !folder.empty() && folder != "." && folder != "..")
    return folder;
  return p.stem().string();
}

SessionTrace sessionTraceFromJournal(const JournalReadResult& journal, const std::string& path,
                                     const std::string& id) {
  SessionTrace trace;
  trace.id = id;
  trace.path = path;
  trace.journal_warning = journal.error;
  if (!journal.records.empty()) trace.t0_ns = journal.records.front().t_ns;
  int task = -1;
  for (size_t i = 0; i < journal.records.size(); ++i) {
    const JournalRecord& record = journal.records[i];
    if (record.type == JournalRecordType::kMarker) followStudyMarker(record, &trace, &task);
    switch (record.type) {
      case JournalRecordType::kPenSample: {
        std::optional<PenSample> sample = decodePenSample(record.payload);
        if (!sample)
          throw StudyInputError(
              path + ": record " + std::to_string(i) + " (pen sample): payload of " +
              std::to_string(record.payload.size()) + " bytes is not a pen sample");
        trace.samples.push_back(*sample);
        trace.sample_records.push_back(i);
        trace.sample_task.push_back(task);
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
        trace.events.push_back({i, record.type, record.t_ns, std::string(device->name, n),
                                task < 0 ? "" : trace.task_ids[size_t(task)]});
        break;
      }
      default:
        trace.events.push_back({i, record.type, record.t_ns, std::string(record.text()),
                                task < 0 ? "" : trace.task_ids[size_t(task)]});
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
  return sessionTraceFromJournal(journal, path, sessionIdForJournal(path));
}

}  // namespace cb
