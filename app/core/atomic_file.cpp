#include "app/core/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <unistd.h>

namespace cb {
namespace {

std::string folderOf(const std::string& path) {
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return dir.empty() ? "." : dir;
}

bool failWith(std::string* error, const std::string& file, const char* step, int err) {
  if (error) *error = file + ": " + step + ": " + std::strerror(err);
  return false;
}

// fsync of an fd opened for reading flushes the file's dirty pages on Linux as well.
bool syncPath(const std::string& path, int flags, std::string* error, const char* step) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) return failWith(error, path, step, errno);
  const bool ok = ::fsync(fd) == 0;
  const int err = errno;
  ::close(fd);
  return ok || failWith(error, path, step, err);
}

}  // namespace

AtomicFileReplacement::AtomicFileReplacement(std::string path) : path_(std::move(path)) {
  static std::atomic<unsigned> counter{0};
  temp_ = path_ + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
}

AtomicFileReplacement::~AtomicFileReplacement() {
  if (!done_) ::unlink(temp_.c_str());
}

bool AtomicFileReplacement::commit(std::string* error) {
  done_ = true;
  if (!syncPath(temp_, O_RDONLY, error, "fsync")) {
    ::unlink(temp_.c_str());
    return false;
  }
  if (::rename(temp_.c_str(), path_.c_str()) != 0) {
    failWith(error, path_, "rename", errno);
    ::unlink(temp_.c_str());
    return false;
  }
  return syncFolderOf(path_, error);
}

bool syncFolderOf(const std::string& path, std::string* error) {
  return syncPath(folderOf(path), O_RDONLY | O_DIRECTORY, error, "fsync of its folder");
}

bool writeFileAtomically(const std::string& path, std::string_view content, std::string* error) {
  AtomicFileReplacement out(path);
  const int fd = ::open(out.tempPath().c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return failWith(error, out.tempPath(), "open", errno);
  size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : ENOSPC;
      ::close(fd);
      return failWith(error, out.tempPath(), "write", err);
    }
    done += size_t(n);
  }
  if (::close(fd) != 0) return failWith(error, out.tempPath(), "close", errno);
  return out.commit(error);
}

}  // namespace cb
