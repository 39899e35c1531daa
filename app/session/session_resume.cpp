#include "app/session/session_resume.h"

#include <filesystem>
#include <fstream>
#include <iterator>

namespace cb {

bool resumeOrStartSession(const std::string& path, const PaintSessionSettings& settings,
                          const BrushConfig& brush, const MappingConfig& mapping,
                          JournalWriter* journal, ResumedSession* out, std::string* error) {
  *out = ResumedSession{};
  std::error_code ec;
  JournalReadResult read;
  if (std::filesystem::exists(path, ec)) {
    read = readJournal(path);
    if (read.version == 0) {
      // Only the remains of a journal whose creation was cut short may be started over.
      std::ifstream in(path, std::ios::binary);
      const std::string head((std::istreambuf_iterator<char>(in)), {});
      if (head.size() >= 8 || std::string("CBJOURNL").compare(0, head.size(), head) != 0) {
        *error = read.error + "; not resuming, and not overwriting it";
        return false;
      }
    }
  }
  bool has_session = false;
  for (const JournalRecord& record : read.records)
    if (record.type == JournalRecordType::kSession) has_session = true;
  if (!has_session && !read.records.empty()) {
    *error = path + ": holds " + std::to_string(read.records.size()) +
             " journal records but no painting session (a pen recording?); not resuming, and "
             "not overwriting it";
    return false;
  }
  if (!has_session) {
    // Nothing to resume (a new file, or one cut before its first record): start afresh.
    if (!journal->open(path)) return *error = journal->error(), false;
    out->session = std::make_unique<PaintSession>(settings, brush, mapping);
    return true;
  }
  SessionReplay replay = replaySession(read, brush, mapping, settings);
  const PaintSessionSettings& recorded = replay.session->settings();
  if (recorded.screen_width != settings.screen_width ||
      recorded.screen_height != settings.screen_height || recorded.grid != settings.grid) {
    *error = path + ": the session was recorded on a " + std::to_string(recorded.screen_width) +
             "x" + std::to_string(recorded.screen_height) + " screen with a " +
             std::to_string(recorded.grid) + "³ grid; this one is " +
             std::to_string(settings.screen_width) + "x" + std::to_string(settings.screen_height) +
             " with " + std::to_string(settings.grid) +
             "³: resume it with the same --size and "
             "--grid";
    return false;
  }
  std::string warning;
  if (!journal->openForAppend(path, &warning)) return *error = journal->error(), false;
  for (const JournalRecord& record : read.records)
    if (record.type == JournalRecordType::kPenSample) out->last_sample_ns = record.t_ns;
  for (const std::string& problem : replay.problems)
    warning += (warning.empty() ? "" : "; ") + problem;
  out->warning = warning;
  out->session = std::move(replay.session);
  out->session->setQuietMapping(false);  // replaySession made it quiet
  out->session->resumeRecordingTo(journal);
  out->replay = std::move(replay);
  out->resumed = true;
  return true;
}

}  // namespace cb
