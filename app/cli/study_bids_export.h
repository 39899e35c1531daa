// `cloudbrush study export --bids DIR`: the given session journals as a BIDS dataset
// (app/study/bids_dataset.h), read one at a time so memory holds one session.
#pragma once

#include <string>
#include <vector>

namespace cb {

// Prints each file written. Returns the exit status: 0; 1 for an error (named on stderr);
// 3 when a journal was damaged (every whole record around the damage is exported, as by the
// other exports). The questionnaires (phenotype/) are described from `protocol_path`, else the
// protocol the first study session names, else the bundled one.
int exportBidsDataset(const std::vector<std::string>& journals,
                      const std::vector<std::string>& session_ids, const std::string& dir,
                      const std::string& protocol_path = "");

}  // namespace cb
