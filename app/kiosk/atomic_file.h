// Replacing a file so that readers see either the old or the new content, never a torn one:
// write a temporary file next to it, fsync, rename over the target, fsync the folder (so the
// rename itself survives a power cut).
#pragma once

#include <string>
#include <string_view>

namespace cb {

// Writes `content` to `path` atomically. The temporary is "<path>.tmp.<pid>" in the same
// directory (rename is atomic only within one file system) and is removed on failure. False with
// *error naming the file and the errno text (e.g. the directory does not exist, disk full).
bool writeFileAtomically(const std::string& path, std::string_view content, std::string* error);

// fsync of the folder holding `path` (a file or folder renamed into it). False with *error.
bool syncFolderOf(const std::string& path, std::string* error);

}  // namespace cb
