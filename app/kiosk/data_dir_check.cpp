#include "app/kiosk/data_dir_check.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace cb {

bool checkDataDir(const std::string& dir, std::string* error) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    *error = dir + ": cannot create the data dir: " + ec.message();
    return false;
  }
  if (!std::filesystem::is_directory(dir, ec)) {
    *error = dir + ": the data dir is not a folder" + (ec ? ": " + ec.message() : "");
    return false;
  }
  if (::access(dir.c_str(), R_OK | W_OK | X_OK) != 0) {
    *error = dir + ": the data dir cannot be used: " + std::strerror(errno);
    return false;
  }
  // A probe: creating a file needs a writable, mounted-read-write file system with free inodes.
  const std::string probe = dir + "/.write-probe-" + std::to_string(::getpid());
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0) {
    *error = dir + ": cannot write a file in the data dir: " + std::strerror(errno);
    return false;
  }
  ::close(fd);
  ::unlink(probe.c_str());
  return true;
}

}  // namespace cb
