// Free and total space of the file system holding a path (statvfs), for the health file.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace cb {

struct DiskSpace {
  uint64_t free_bytes = 0;  // available to an unprivileged process (f_bavail)
  uint64_t total_bytes = 0;
};

// nullopt with *error ("PATH: statvfs: No such file or directory") when the path cannot be
// examined.
std::optional<DiskSpace> diskSpaceAt(const std::string& path, std::string* error);

}  // namespace cb
