// A real small file system for the kiosk's disk-full tests: a tmpfs of a few megabytes mounted
// on a fresh folder (needs root: CAP_SYS_ADMIN), unmounted again at the end. fillLeaving()
// writes a filler file until only so many bytes are free (statvfs), or until the kernel answers
// ENOSPC: the disk is then really full, as a month of visitors would leave it.
#pragma once

#include <fcntl.h>
#include <sys/mount.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace cb::test {

class SmallTmpfs {
 public:
  SmallTmpfs(const std::string& dir, uint64_t bytes) : dir_(dir) {
    if (::geteuid() != 0) {
      why_ = "needs root to mount a " + std::to_string(bytes >> 20) +
             " MB tmpfs (a real full file system); run the test as root";
      return;
    }
    std::error_code ec;
    std::filesystem::create_directories(dir_, ec);
    const std::string options = "size=" + std::to_string(bytes) + ",mode=0755";
    if (::mount("tmpfs", dir_.c_str(), "tmpfs", 0, options.c_str()) != 0) {
      why_ = "mount -t tmpfs " + dir_ + ": " + std::strerror(errno);
      return;
    }
    mounted_ = true;
  }
  ~SmallTmpfs() {
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
    std::error_code ec;
    std::filesystem::remove(dir_, ec);
  }
  SmallTmpfs(const SmallTmpfs&) = delete;
  SmallTmpfs& operator=(const SmallTmpfs&) = delete;

  bool mounted() const { return mounted_; }
  const std::string& why() const { return why_; }
  const std::string& dir() const { return dir_; }
  uint64_t freeBytes() const {
    struct statvfs s {};
    ::statvfs(dir_.c_str(), &s);
    return uint64_t(s.f_bavail) * s.f_frsize;
  }
  // Appends to `path` until at most `leave` bytes are free (0: until ENOSPC). Returns the bytes
  // written.
  uint64_t fillLeaving(uint64_t leave, const std::string& path) const {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd < 0) return 0;
    const std::vector<char> block(64 * 1024, 'f');
    uint64_t written = 0;
    for (;;) {
      const uint64_t free = freeBytes();
      if (leave > 0 && free <= leave) break;
      size_t n = block.size();
      if (leave > 0 && free - leave < n) n = size_t(free - leave);
      const ssize_t w = ::write(fd, block.data(), n);
      if (w <= 0) break;  // ENOSPC
      written += uint64_t(w);
    }
    ::close(fd);
    return written;
  }

 private:
  std::string dir_;
  std::string why_;
  bool mounted_ = false;
};

}  // namespace cb::test
