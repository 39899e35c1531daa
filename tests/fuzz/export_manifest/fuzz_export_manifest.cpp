// Fuzz target: the outside text a sharded study export reads — a manifest of journals (without
// looking at the file system) and a shard's record (shard.txt) — through their parsers; a
// record that parses is written back and must read back the same.
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "app/study/export_shards.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    std::istringstream in(text);
    (void)cb::parseExportManifest(in, "fuzz", "/base", false);
  } catch (const cb::StudyInputError&) {
  }
  try {
    const cb::ShardRecord record = cb::parseShardRecord(text, "fuzz");
    const cb::ShardRecord back = cb::parseShardRecord(cb::shardRecordText(record), "again");
    if (back.session_ids != record.session_ids || back.damaged != record.damaged ||
        back.protocol != record.protocol || back.sessions.begin != record.sessions.begin ||
        back.sessions.end != record.sessions.end || back.spec.index != record.spec.index)
      std::abort();
  } catch (const cb::StudyInputError&) {
  }
  return 0;
}
