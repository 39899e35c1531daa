// A study export split over machines (a Slurm job array, docs/study-on-slurm.md): a manifest
// lists the sessions' journals in the study's order; shard I of N exports one contiguous block
// of them as parts (rows only, no headers); the merge joins every shard's parts in order into
// exactly the files one machine exporting the whole manifest writes.
#pragma once

#include <cstddef>
#include <istream>
#include <string>
#include <vector>

#include "app/study/session_trace.h"  // StudyInputError

namespace cb {

// The journals a manifest lists, one per line, in the study's order. Blank lines and lines
// starting with '#' are skipped; leading and trailing spaces are trimmed; a relative path is
// relative to the manifest's folder (`base_dir`). A journal that does not exist, or a line
// with a NUL or control byte, raises StudyInputError "NAME:LINE: journal: ...". An empty
// manifest is an error too.
std::vector<std::string> parseExportManifest(std::istream& in, const std::string& name,
                                             const std::string& base_dir,
                                             bool check_files_exist = true);
std::vector<std::string> readExportManifest(const std::string& path);

// "I/N" with 1 <= I <= N <= kMaxShards.
struct ShardSpec {
  int index = 1;
  int count = 1;
};
constexpr int kMaxShards = 100000;
bool parseShardSpec(const std::string& text, ShardSpec* spec, std::string* error);

// The sessions [begin, end) of `sessions` that shard `spec` exports: contiguous blocks whose
// sizes differ by at most one, in order, so that joining the shards' parts 1..N gives the
// sessions in the manifest's order. A shard may get none (more shards than sessions).
struct SessionRange {
  size_t begin = 0;
  size_t end = 0;
};
SessionRange shardRange(size_t sessions, const ShardSpec& spec);

// OUT/shards/I-of-N: where shard I of N leaves its parts and its record.
std::string shardFolder(const std::string& out, const ShardSpec& spec);

// What a finished shard leaves beside its parts (shard.txt, written last and atomically, so a
// shard killed before the end has none and the merge refuses it).
struct ShardRecord {
  ShardSpec spec;
  SessionRange sessions;
  std::vector<std::string> session_ids;  // of sessions [begin, end), in order
  std::string protocol;                  // the first session's protocol file, or empty
  std::vector<std::string> damaged;      // journals exported around a damaged record
};
std::string shardRecordText(const ShardRecord& record);
// Raises StudyInputError "NAME:LINE: field: ..." on a malformed record.
ShardRecord parseShardRecord(const std::string& text, const std::string& name);

}  // namespace cb
