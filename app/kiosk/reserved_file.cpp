#include "app/kiosk/reserved_file.h"

#include <fcntl.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "app/core/atomic_file.h"

namespace cb {
namespace {

// Writes `content` over the start of `spare` (made when missing) without giving up its blocks:
// blocks for the content are reserved first (fallocate, keeping the size; it fails harmlessly
// on a full disk when they are already there), and the truncation to the content's length frees
// only whole blocks past it.
bool writeSpare(const std::string& spare, std::string_view content, std::string* why) {
  const int fd = ::open(spare.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) {
    *why = spare + ": open: " + std::strerror(errno);
    return false;
  }
  ::fallocate(fd, FALLOC_FL_KEEP_SIZE, 0, off_t(content.size()));
  size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::pwrite(fd, content.data() + done, content.size() - done, off_t(done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      *why = spare + ": write: " + std::strerror(n < 0 ? errno : ENOSPC);
      ::close(fd);
      return false;
    }
    done += size_t(n);
  }
  const bool ok = ::ftruncate(fd, off_t(content.size())) == 0 && ::fdatasync(fd) == 0;
  if (!ok) *why = spare + ": truncate/sync: " + std::strerror(errno);
  ::close(fd);
  return ok;
}

}  // namespace

bool writeFileKeepingBlocks(const std::string& path, std::string_view content, std::string* error) {
  const std::string spare = path + ".spare";
  std::string why;
  struct stat live {};
  if (::stat(path.c_str(), &live) == 0 && writeSpare(spare, content, &why)) {
    if (::renameat2(AT_FDCWD, spare.c_str(), AT_FDCWD, path.c_str(), RENAME_EXCHANGE) == 0)
      return syncFolderOf(path, error);
    why = path + ": exchange with its spare: " + std::strerror(errno);
  }
  // The first write (no live copy yet) or no exchange here: the temporary-and-rename writer.
  // Its new file makes the spare of the next write.
  if (writeFileAtomically(path, content, error)) return true;
  if (error && !why.empty()) *error += " (and through " + why + ")";
  return false;
}

}  // namespace cb
