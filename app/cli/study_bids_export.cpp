#include "app/cli/study_bids_export.h"

#include <cstdio>

#include "app/study/bids_dataset.h"
#include "app/study/session_trace.h"
#include "drivers/core/journal.h"

namespace cb {

int exportBidsDataset(const std::vector<std::string>& journals,
                      const std::vector<std::string>& session_ids, const std::string& dir) {
  const auto fail = [](const std::string& message) {
    std::fprintf(stderr, "cloudbrush study: --bids: %s\n", message.c_str());
    return 1;
  };
  BidsDatasetWriter writer(dir);
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
      if (!writer.addSession(sessionTraceFromJournal(journal, journals[i], session_ids[i]), &error))
        return fail(error);
    } catch (const StudyInputError& e) {
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
