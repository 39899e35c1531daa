// The clouds a participant saved with the painter's Save during a study session: the files of
// the session folder's saved/ beside its journal (app/shell/study/study_run_screen.h). Every
// export copies them through here, byte for byte, so `study export --out` and `--bids` carry the
// same files.
#pragma once

#include <string>
#include <vector>

namespace cb {

// saved/'s regular files beside `journal_path` (hidden ones, such as a writer's temporary, left
// out), in name order; none when there is no saved/. False with *error when it cannot be listed.
bool savedCloudFiles(const std::string& journal_path, std::vector<std::string>* files,
                     std::string* error);

// Copies them into `to_folder` (made when there is something to copy; its entry synced), each
// file atomically (app/core/atomic_file.h). Appends each written path to `written` (may be
// null). False with *error naming the file.
bool copySavedClouds(const std::string& journal_path, const std::string& to_folder,
                     std::vector<std::string>* written, std::string* error);

}  // namespace cb
