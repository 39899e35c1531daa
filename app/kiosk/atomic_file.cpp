#include "app/kiosk/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace cb {

bool writeFileAtomically(const std::string& path, std::string_view content, std::string* error) {
  const std::string temp = path + ".tmp." + std::to_string(::getpid());
  auto fail = [&](const std::string& file, const char* step, int err) {
    if (error) *error = file + ": " + step + ": " + std::strerror(err);
    ::unlink(temp.c_str());
    return false;
  };
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int err = errno;
    if (error) *error = temp + ": open: " + std::strerror(err);
    return false;
  }
  size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      ::close(fd);
      return fail(temp, "write", err);
    }
    done += static_cast<size_t>(n);
  }
  if (::fsync(fd) != 0) {
    const int err = errno;
    ::close(fd);
    return fail(temp, "fsync", err);
  }
  if (::close(fd) != 0) return fail(temp, "close", errno);
  if (::rename(temp.c_str(), path.c_str()) != 0) return fail(path, "rename", errno);
  return syncFolderOf(path, error);
}

bool syncFolderOf(const std::string& path, std::string* error) {
  const std::string::size_type slash = path.rfind('/');
  const std::string dir = slash == std::string::npos ? "."
                          : slash == 0               ? "/"
                                                     : path.substr(0, slash);
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0 || ::fsync(fd) != 0) {
    const int err = errno;
    if (fd >= 0) ::close(fd);
    if (error) *error = dir + ": fsync of the folder: " + std::strerror(err);
    return false;
  }
  ::close(fd);
  return true;
}

}  // namespace cb
