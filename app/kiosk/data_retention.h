// Deleting what the kiosk must not keep longer than configured: session journals older
// than [journals] keep_days in config/kiosk.toml. Age is the file's modification time.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace cb {

// Deletes the regular files directly in `dir` ending in `extension` (e.g. ".cbj") whose last
// write is more than `keep_days` before `now`; returns their paths. A missing dir deletes
// nothing; the first failure is put in *error and the rest still tried.
std::vector<std::string> deleteFilesOlderThan(const std::string& dir, const std::string& extension,
                                              double keep_days, std::filesystem::file_time_type now,
                                              std::string* error);

}  // namespace cb
