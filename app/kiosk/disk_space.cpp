#include "app/kiosk/disk_space.h"

#include <sys/statvfs.h>

#include <cerrno>
#include <cstring>

namespace cb {

std::optional<DiskSpace> diskSpaceAt(const std::string& path, std::string* error) {
  struct statvfs info {};
  if (::statvfs(path.c_str(), &info) != 0) {
    if (error) *error = path + ": statvfs: " + std::strerror(errno);
    return std::nullopt;
  }
  return DiskSpace{static_cast<uint64_t>(info.f_bavail) * info.f_frsize,
                   static_cast<uint64_t>(info.f_blocks) * info.f_frsize};
}

}  // namespace cb
