#include "app/cli/study_trace_export.h"

#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "app/brush/brush_config.h"
#include "app/cli/study_export_files.h"
#include "app/core/config_paths.h"
#include "app/mapping/mapping_config.h"
#include "app/session/paint_session.h"
#include "app/session/session_replay.h"
#include "app/study/inkml_writer.h"
#include "app/study/saved_clouds.h"
#include "app/study/session_trace.h"
#include "app/study/trace_csv.h"
#include "app/study/trial_table.h"

namespace cb {
namespace {

namespace fs = std::filesystem;

// The trace files, in the order their streams are kept.
const char* const kTraceFiles[] = {"traces.inkml", "samples.csv", "strokes.csv", "events.csv",
                                   "trials.csv"};
constexpr size_t kTraceFileCount = std::size(kTraceFiles);

// The five trace files being written under one folder. `whole` files get their headers (and
// InkML's opening and closing); a shard's parts hold rows only.
class TraceFiles {
 public:
  bool open(const fs::path& dir, std::string* error) {
    for (const char* name : kTraceFiles) {
      files_.push_back(std::make_unique<AtomicStream>((dir / name).string()));
      if (!files_.back()->out) return *error = (dir / name).string() + ": cannot create", false;
    }
    return true;
  }
  std::ofstream& stream(size_t k) { return files_[k]->out; }
  void writeHeaders() {
    beginInkml(stream(0));
    writeSamplesCsvHeader(stream(1));
    writeStrokesCsvHeader(stream(2));
    writeEventsCsvHeader(stream(3));
    writeTrialsCsvHeader(stream(4));
  }
  void writeSession(const SessionTrace& trace, size_t position) {
    writeInkmlSession(stream(0), trace, position);
    writeSamplesCsvRows(stream(1), trace);
    writeStrokesCsvRows(stream(2), trace);
    writeEventsCsvRows(stream(3), trace);
    writeTrialsCsvRows(stream(4), trace);
  }
  void writeFooters() { endInkml(stream(0)); }
  bool commit(std::string* error, bool announce) {
    for (auto& file : files_)
      if (!file->commit(error, announce)) return false;
    return true;
  }

 private:
  std::vector<std::unique_ptr<AtomicStream>> files_;
};

// Brush and mapping for replaying journals into volumes (the configuration directory's).
struct ReplayConfig {
  BrushConfig brush;
  MappingConfig mapping;
};

int loadReplayConfig(ReplayConfig* config) {
  const std::string mapping_path = configFile("mapping.toml");
  try {
    if (fs::exists(mapping_path)) config->mapping = loadMappingConfig(mapping_path);
  } catch (const std::exception& e) {
    return studyFail(e.what());
  }
  config->brush = loadDefaultBrushConfig();
  return 0;
}

// Session `i` of the request into `files` (and its volume and render). 0 or the exit status;
// a damaged journal is added to *damaged, and the first protocol found to *protocol.
int exportSession(const TraceExportRequest& request, size_t i, const ReplayConfig* replay_config,
                  TraceFiles* files, std::vector<std::string>* damaged, std::string* protocol) {
  const std::string& path = request.journals[i];
  const JournalReadResult journal = readJournal(path);
  if (journal.records.empty())
    return studyFail(path + ": no journal records" +
                     (journal.error.empty() ? "" : " (" + journal.error + ")"));
  if (!journal.error.empty()) {
    std::fprintf(stderr, "cloudbrush study: %s (exporting every whole record around it)\n",
                 journal.error.c_str());
    damaged->push_back(path);
  }
  try {
    const SessionTrace trace = sessionTraceFromJournal(journal, path, request.ids[i]);
    if (protocol->empty()) *protocol = protocolFileOf(trace);
    files->writeSession(trace, i);
  } catch (const StudyInputError& e) {
    return studyFail(e.what());
  }
  // The clouds the participant saved with the painter's Save, as --bids copies them.
  std::vector<std::string> saved;
  std::string error;
  if (!copySavedClouds(path, (fs::path(request.out) / "saved" / request.ids[i]).string(), &saved,
                       &error))
    return studyFail(error);
  for (const std::string& file : saved) std::printf("%s\n", file.c_str());
  if (!replay_config) return 0;
  const SessionReplay replay = replaySession(journal, replay_config->brush, replay_config->mapping);
  for (const std::string& problem : replay.problems)
    std::fprintf(stderr, "cloudbrush study: %s: %s\n", path.c_str(), problem.c_str());
  if (!replay.session) return studyFail(path + ": nothing could be replayed");
  const PaintSession& session = *replay.session;
  const fs::path dir(request.out);
  return exportVolumeAndRender(session.volume(), session.camera(), &session.light(),
                               (dir / "volumes").string(), (dir / "renders").string(),
                               request.ids[i], true, request.width, request.height);
}

// Exit status 3 naming the damaged journals, or 0.
int damagedStatus(const std::vector<std::string>& damaged) {
  if (damaged.empty()) return 0;
  // The exports hold every whole record, but a damaged journal lost the ones it skipped: say so
  // in the exit status, as replay does.
  return studyFail(std::to_string(damaged.size()) + " journal(s) damaged (" + damaged[0] +
                       (damaged.size() > 1 ? ", ..." : "") +
                       "): the exports lack their skipped bytes",
                   3);
}

std::string readWhole(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The finished shards' records under OUT/shards, in order 1..N; an error names what is missing.
bool readShardRecords(const TraceExportRequest& request, std::vector<ShardRecord>* records,
                      std::string* error) {
  const fs::path shards = fs::path(request.out) / "shards";
  std::error_code ec;
  int count = 0;
  for (const auto& entry : fs::directory_iterator(shards, ec)) {
    const std::string name = entry.path().filename().string();
    const size_t of = name.find("-of-");
    ShardSpec spec;
    std::string ignored;
    if (of == std::string::npos ||
        !parseShardSpec(name.substr(0, of) + "/" + name.substr(of + 4), &spec, &ignored))
      continue;
    if (count != 0 && spec.count != count)
      return *error = shards.string() + ": shards of two splits (" + std::to_string(count) +
                      " and " + std::to_string(spec.count) + "); remove the stale ones",
             false;
    count = spec.count;
  }
  if (ec || count == 0) return *error = shards.string() + ": no shards to merge", false;
  for (int i = 1; i <= count; ++i) {
    const fs::path record = fs::path(shardFolder(request.out, {i, count})) / "shard.txt";
    if (!fs::exists(record))
      return *error = record.string() + ": missing (shard " + std::to_string(i) + " of " +
                      std::to_string(count) + " has not finished)",
             false;
    try {
      records->push_back(parseShardRecord(readWhole(record), record.string()));
    } catch (const StudyInputError& e) {
      return *error = e.what(), false;
    }
    const ShardRecord& r = records->back();
    const SessionRange expected = shardRange(request.journals.size(), {i, count});
    if (r.sessions.begin != expected.begin || r.sessions.end != expected.end ||
        !std::equal(r.session_ids.begin(), r.session_ids.end(),
                    request.ids.begin() + long(expected.begin)))
      return *error = record.string() + ": its sessions are not this manifest's " +
                      std::to_string(expected.begin) + ".." + std::to_string(expected.end),
             false;
  }
  return true;
}

}  // namespace

int exportStudyTraces(const TraceExportRequest& request) {
  ReplayConfig replay_config;
  if (request.volumes)
    if (const int status = loadReplayConfig(&replay_config)) return status;
  const bool whole = !request.shard;
  const fs::path dir =
      whole ? fs::path(request.out) : fs::path(shardFolder(request.out, *request.shard));
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return studyFail(dir.string() + ": cannot create the directory: " + ec.message());
  TraceFiles files;
  std::string error;
  if (!files.open(dir, &error)) return studyFail(error);
  if (whole) files.writeHeaders();
  const SessionRange range = whole ? SessionRange{0, request.journals.size()}
                                   : shardRange(request.journals.size(), *request.shard);
  std::vector<std::string> damaged;
  std::string protocol = request.protocol;
  // One session at a time, so memory holds one session.
  for (size_t i = range.begin; i < range.end; ++i) {
    if (request.journals.size() > 1)
      std::fprintf(stderr, "cloudbrush study: %s (%zu of %zu)\n", request.journals[i].c_str(),
                   i + 1, request.journals.size());
    if (const int status = exportSession(request, i, request.volumes ? &replay_config : nullptr,
                                         &files, &damaged, &protocol))
      return status;
  }
  if (whole) files.writeFooters();
  if (!files.commit(&error, whole)) return studyFail(error);
  if (whole) {
    if (const int code = writeCodebook(protocol, (dir / "codebook.csv").string())) return code;
  } else {
    ShardRecord record{*request.shard, range, {}, protocol, damaged};
    record.session_ids.assign(request.ids.begin() + long(range.begin),
                              request.ids.begin() + long(range.end));
    // Written last: the merge takes a shard with this record as finished.
    if (!writeFileAtomically((dir / "shard.txt").string(), shardRecordText(record), &error))
      return studyFail(error);
    std::printf("%s\n", (dir / "shard.txt").string().c_str());
  }
  return damagedStatus(damaged);
}

int mergeStudyTraceShards(const TraceExportRequest& request) {
  std::vector<ShardRecord> records;
  std::string error;
  if (!readShardRecords(request, &records, &error)) return studyFail("export --merge: " + error);
  const fs::path dir(request.out);
  TraceFiles files;
  if (!files.open(dir, &error)) return studyFail(error);
  files.writeHeaders();
  std::string protocol = request.protocol;
  std::vector<std::string> damaged;
  for (const ShardRecord& record : records) {
    const fs::path folder(shardFolder(request.out, record.spec));
    for (size_t k = 0; k < kTraceFileCount; ++k) {
      std::ifstream part(folder / kTraceFiles[k], std::ios::binary);
      if (!part) return studyFail((folder / kTraceFiles[k]).string() + ": cannot read the part");
      // (Inserting an empty buffer would set the output's failbit.)
      if (part.peek() != std::char_traits<char>::eof()) files.stream(k) << part.rdbuf();
    }
    if (protocol.empty()) protocol = record.protocol;
    damaged.insert(damaged.end(), record.damaged.begin(), record.damaged.end());
  }
  files.writeFooters();
  if (!files.commit(&error, true)) return studyFail(error);
  if (const int code = writeCodebook(protocol, (dir / "codebook.csv").string())) return code;
  std::error_code ec;
  fs::remove_all(dir / "shards", ec);
  if (ec)
    std::fprintf(stderr, "cloudbrush study: %s: not removed: %s\n",
                 (dir / "shards").string().c_str(), ec.message().c_str());
  return damagedStatus(damaged);
}

}  // namespace cb
