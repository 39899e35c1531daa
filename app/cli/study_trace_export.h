// `cloudbrush study export`: the pen traces of study sessions (InkML, samples, strokes, events,
// trials, the codebook) and, with --volumes, each session's replayed volume and render — for
// the whole list of journals on one machine, or one shard of a manifest and the merge of every
// shard's parts (app/study/export_shards.h).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "app/study/export_shards.h"

namespace cb {

struct TraceExportRequest {
  std::vector<std::string> journals;  // in the study's order
  std::vector<std::string> ids;       // each journal's session id (sessionIdForJournal)
  std::string out;                    // the folder
  bool volumes = false;
  int width = 1280, height = 720;  // of the renders
  std::string protocol;            // the codebook's protocol; empty: the first session's
  std::optional<ShardSpec> shard;  // export only this shard, as parts under OUT/shards/
};

// Exports the request's journals (or its shard's). Prints each file written. Returns the exit
// status: 0; 1 for an error (named on stderr); 3 when a journal was damaged (every whole record
// around the damage is exported).
int exportStudyTraces(const TraceExportRequest& request);

// Joins OUT/shards/*-of-N (every shard of one N, each finished) into OUT's files, byte for byte
// what one machine exporting the whole request writes, then removes OUT/shards. The shards'
// session ids must be the request's. Exit status as exportStudyTraces (3: a shard's journal was
// damaged).
int mergeStudyTraceShards(const TraceExportRequest& request);

}  // namespace cb
