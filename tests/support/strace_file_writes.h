// Reading an `strace -f -e trace=%file` log: every path a process (and its threads and
// children) opened for writing, created, renamed or removed, and which of them lie outside the
// directories it was allowed to write into. Used by the kiosk's confinement checks.
#pragma once

#include <string>
#include <vector>

namespace cb::test {

struct FileWrites {
  size_t writes = 0;                 // successful writing calls on paths (devices aside)
  std::vector<std::string> outside;  // their strace lines whose path is outside `allowed`
};

// `trace` is the log's text; relative paths are resolved against `cwd`. A call counts as writing
// when it is an open*() with O_WRONLY, O_RDWR or O_CREAT, or a mkdir, rename, unlink or rmdir;
// failed calls (`= -1`) and paths under /dev/ (the render node is opened read-write) are left out.
FileWrites fileWritesOutside(const std::string& trace, const std::string& cwd,
                             const std::vector<std::string>& allowed);

}  // namespace cb::test
