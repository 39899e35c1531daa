// A session journal read for analysis: the device, every raw pen sample and every non-sample
// record (UI/mode changes, markers, calibration, session metadata) in journal order, without
// replaying anything. This is what the pen-trace exports (InkML, CSV) are made from.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "drivers/core/journal.h"
#include "drivers/core/pen_sample.h"

namespace cb {

struct StudyInputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// One non-sample record, kept as the journal has it.
struct TraceEvent {
  size_t record_index = 0;  // position in the journal (0 = first record after the header)
  JournalRecordType type{};
  int64_t t_ns = 0;
  std::string text;  // the payload as text (device records: the device's name)
  std::string task;  // the study task running when it was written, else empty
};

struct SessionTrace {
  std::string id;    // the journal's file name without extension (e.g. "2026-11-22T10-00-00")
  std::string path;  // where it was read from
  // The study participant's id (the runner's `study.info` marker), else empty.
  std::string participant;
  // The study task each sample was written in (`study.stage-begin stage=task task=ID` until the
  // stage's end): an index into task_ids, -1 outside tasks.
  std::vector<std::string> task_ids;
  std::vector<int> sample_task;
  std::optional<PenDeviceInfo> device;  // the first Device record, if any
  std::vector<PenSample> samples;
  std::vector<size_t> sample_records;  // journal record index of each sample
  std::vector<TraceEvent> events;
  std::string journal_warning;  // the reader's message for a torn/corrupt tail, else empty
  int64_t t0_ns = 0;            // t_ns of the first record: the session's time origin
};

// t − origin in nanoseconds, saturated to the int64 range (journals from elsewhere may hold any
// timestamps; the plain difference could overflow).
int64_t elapsedNs(int64_t t, int64_t origin);

// The id of the session a journal holds: a study session's journal (`session.cbj` in its
// folder `<participant>-<start>`) is named by its folder, any other by its file name.
std::string sessionIdForJournal(const std::string& path);

// The sample's task id, or empty outside tasks.
inline std::string sampleTask(const SessionTrace& trace, size_t sample) {
  const int t = sample < trace.sample_task.size() ? trace.sample_task[sample] : -1;
  return t < 0 ? std::string() : trace.task_ids[size_t(t)];
}

// Reads `path`. A file that is not a journal, or has no records at all, raises StudyInputError
// naming the file; a damaged tail keeps the intact prefix and sets journal_warning. A pen-sample
// record whose payload has the wrong size raises StudyInputError naming the record.
SessionTrace loadSessionTrace(const std::string& path);
// The same from an already parsed journal (`path` and `id` as given).
SessionTrace sessionTraceFromJournal(const JournalReadResult& journal, const std::string& path,
                                     const std::string& id);

}  // namespace cb
