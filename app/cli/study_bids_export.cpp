#include "app/cli/study_bids_export.h"

#include <cstdio>
#include <filesystem>

#include "app/study/bids_dataset.h"
#include "app/study/protocol.h"
#include "app/study/session_trace.h"
#include "app/study/study_session_record.h"
#include "drivers/core/journal.h"

namespace cb {
namespace {

// The protocol file a study session's study.info names, when it is still there, else "".
std::string namedProtocolFile(const SessionTrace& trace) {
  for (const TraceEvent& e : trace.events) {
    StudySessionInfo info;
    if (e.type == JournalRecordType::kMarker && parseStudyInfoMarker(e.text, &info))
      return std::filesystem::exists(info.protocol_file) ? info.protocol_file : "";
  }
  return "";
}

}  // namespace

int exportBidsDataset(const std::vector<std::string>& journals,
                      const std::vector<std::string>& session_ids, const std::string& dir,
                      const std::string& protocol_path) {
  const auto fail = [](const std::string& message) {
    std::fprintf(stderr, "cloudbrush study: --bids: %s\n", message.c_str());
    return 1;
  };
  StudyProtocol protocol;  // loaded with the first session; the writer reads it in finish()
  BidsDatasetWriter writer(dir, &protocol);
  size_t printed = 0, damaged = 0;
  const auto print = [&] {
    for (; printed < writer.written().size(); ++printed)
      std::printf("%s\n", writer.written()[printed].c_str());
  };
  std::string error;
  for (size_t i = 0; i < journals.size(); ++i) {
    const JournalReadResult journal = readJournal(journals[i]);
    if (journal.records.empty())
      return fail(journals[i] + ": no journal records" +
                  (journal.error.empty() ? "" : " (" + journal.error + ")"));
    if (!journal.error.empty()) {
      std::fprintf(stderr, "cloudbrush study: --bids: %s (exporting every whole record)\n",
                   journal.error.c_str());
      ++damaged;
    }
    try {
      const SessionTrace trace = sessionTraceFromJournal(journal, journals[i], session_ids[i]);
      if (i == 0) {
        std::string path = protocol_path.empty() ? namedProtocolFile(trace) : protocol_path;
        if (path.empty()) path = defaultStudyProtocolPath();
        protocol = loadStudyProtocol(path);
        std::fprintf(stderr, "cloudbrush study: --bids: questionnaires of the protocol %s\n",
                     path.c_str());
      }
      if (!writer.addSession(trace, &error)) return fail(error);
    } catch (const std::exception& e) {
      return fail(e.what());
    }
    print();
  }
  if (!writer.finish(&error)) return fail(error);
  print();
  if (damaged == 0) return 0;
  std::fprintf(stderr,
               "cloudbrush study: --bids: %zu journal(s) damaged: the dataset lacks their "
               "skipped bytes\n",
               damaged);
  return 3;
}

}  // namespace cb
