// Writing a journal: append-only records that reach the disk whole or not at all.
#include <cerrno>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <unistd.h>

#include "drivers/core/clock.h"
#include "drivers/core/journal.h"
#include "drivers/core/journal_framing.h"

namespace cb {
namespace {

std::string directoryOf(const std::string& path) {
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return dir.empty() ? "." : dir;
}

// The directory entry of a new file reaches the disk only when its directory is synced.
void syncDirectory(const std::string& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

bool writeAll(int fd, const uint8_t* data, size_t n, uint64_t offset) {
  while (n > 0) {
    const ssize_t w = ::pwrite(fd, data, n, off_t(offset));
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) {
      if (w == 0) errno = ENOSPC;
      return false;
    }
    data += w, n -= size_t(w), offset += uint64_t(w);
  }
  return true;
}

// Copies a journal's damaged tail to a file of its own next to it (temporary name, fsync,
// rename, fsync of the folder), so cutting it from the journal loses nothing.
bool keepTailAside(const std::string& path, uint64_t from, std::string* aside, std::string* error) {
  const int in = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0)
    return *error = path + ": cannot read its damaged tail: " + std::strerror(errno), false;
  std::vector<uint8_t> bytes;
  uint8_t buf[1 << 16];
  for (uint64_t at = from;;) {
    const ssize_t r = ::pread(in, buf, sizeof buf, off_t(at));
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) {
      *error = path + ": cannot read its damaged tail: " + std::strerror(errno);
      ::close(in);
      return false;
    }
    if (r == 0) break;
    bytes.insert(bytes.end(), buf, buf + r), at += uint64_t(r);
  }
  ::close(in);
  *aside = path + ".damaged-at-" + std::to_string(from);
  const std::string temp = *aside + ".tmp";
  const int out = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  bool ok = out >= 0 && writeAll(out, bytes.data(), bytes.size(), 0) && ::fsync(out) == 0;
  const int err = errno;
  if (out >= 0 && ::close(out) != 0 && ok) ok = false;
  if (ok && ::rename(temp.c_str(), aside->c_str()) == 0) {
    syncDirectory(directoryOf(path));
    return true;
  }
  *error = *aside + ": cannot keep the journal's damaged tail aside: " + std::strerror(err);
  ::unlink(temp.c_str());
  return false;
}

}  // namespace

JournalWriter::~JournalWriter() {
  close();
}

void JournalWriter::reset() {
  held_.clear();
  synced_end_ = 0;
  written_ = 0;
  failing_ = trim_ = false;
  dropped_ = 0;
  unsynced_since_ns_ = -1;
}

bool JournalWriter::fail(const std::string& what, int err) {
  error_ = "journal " + path_ + ": " + what + ": " + std::strerror(err);
  return false;
}

bool JournalWriter::open(const std::string& path) {
  close();
  path_ = path;
  version_ = kJournalVersion;
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) return fail("cannot create", errno);
  held_ = journalFileHeader(version_);
  if (!sync()) {
    error_ = "journal " + path_ + ": cannot write header: " + error_;
    ::close(fd_);
    fd_ = -1;
    return false;
  }
  syncDirectory(directoryOf(path));
  return true;
}

bool JournalWriter::openForAppend(const std::string& path, std::string* warning) {
  close();
  warning->clear();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec) ||
      std::filesystem::file_size(path, ec) < kJournalHeaderSize)
    return open(path);
  const JournalReadResult read = readJournal(path);
  if (read.version == 0 || read.version > kJournalVersion) {
    error_ =
        read.error.empty() ? "journal " + path + ": not a journal this version writes" : read.error;
    return false;
  }
  path_ = path;
  version_ = read.version;
  const uint64_t size = std::filesystem::file_size(path, ec);
  if (read.intact_bytes < size) {
    std::string aside;
    if (!keepTailAside(path, read.intact_bytes, &aside, &error_)) return false;
    *warning = "; its last " + std::to_string(size - read.intact_bytes) +
               " bytes (a damaged tail after the last whole record, byte " +
               std::to_string(read.intact_bytes) + ") were moved to " + aside +
               " and cut from the journal";
  }
  if (!read.error.empty()) *warning = read.error + *warning;
  fd_ = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
  if (fd_ < 0) return fail("cannot open for appending", errno);
  if (read.intact_bytes < size && ::ftruncate(fd_, off_t(read.intact_bytes)) != 0) {
    fail("cannot cut its damaged tail (kept aside)", errno);
    ::close(fd_);
    fd_ = -1;
    return false;
  }
  synced_end_ = read.intact_bytes;
  if (::fsync(fd_) != 0) {
    fail("cannot sync", errno);
    ::close(fd_);
    fd_ = -1;
    return false;
  }
  return true;
}

bool JournalWriter::writeHeld() {
  const size_t start = written_;  // a record boundary
  if (!writeAll(fd_, held_.data() + start, held_.size() - start, synced_end_ + start)) {
    const int err = errno;
    // Cut what this attempt wrote, so the file ends after its last whole record; if even that
    // fails, the next successful write starts at the same offset and trims after itself.
    trim_ = ::ftruncate(fd_, off_t(synced_end_ + start)) != 0;
    failing_ = true;
    return fail("write failed, " + std::to_string(held_.size() - start) +
                    " bytes of records held in memory to be written again",
                err);
  }
  written_ = held_.size();
  if (trim_ && ::ftruncate(fd_, off_t(synced_end_ + written_)) == 0) trim_ = false;
  failing_ = false;
  return true;
}

bool JournalWriter::append(JournalRecordType type, int64_t t_ns, const uint8_t* data, size_t n) {
  if (fd_ < 0) {
    error_ = "journal: append on a closed writer";
    return false;
  }
  if (held_.size() + journalRecordSize(version_, n) > kMaxHeldBytes) {
    ++dropped_;
    error_ = "journal " + path_ + ": " + std::to_string(dropped_) +
             " records lost: writing has failed until " + std::to_string(held_.size()) +
             " bytes were held in memory";
    return false;
  }
  appendJournalRecord(version_, uint32_t(type), t_ns, data, n, &held_);
  const int64_t now = MonotonicClock().nowNs();
  if (unsynced_since_ns_ < 0) unsynced_since_ns_ = now;
  if (!writeHeld()) return false;
  return syncIfDue(now);
}

bool JournalWriter::appendPenSample(const PenSample& s) {
  auto p = encodePenSample(s);
  return append(JournalRecordType::kPenSample, s.t_ns, p.data(), p.size());
}

bool JournalWriter::sync() {
  if (fd_ < 0) return false;
  if (!writeHeld()) return false;
  if (::fsync(fd_) != 0) {
    // After a failed fsync the kernel may have dropped the dirty pages: write everything since
    // the last good fsync again at the next attempt.
    written_ = 0;
    failing_ = true;
    return fail("sync failed, records since the last sync held to be written again", errno);
  }
  synced_end_ += written_;
  held_.clear();
  written_ = 0;
  unsynced_since_ns_ = -1;
  ++syncs_;
  return true;
}

bool JournalWriter::syncIfDue(int64_t now_ns, int64_t interval_ns) {
  if (fd_ < 0 || unsynced_since_ns_ < 0 || now_ns - unsynced_since_ns_ < interval_ns) return true;
  return sync();
}

void JournalWriter::close() {
  if (fd_ >= 0) {
    sync();
    ::close(fd_);
    fd_ = -1;
  }
  reset();
}

}  // namespace cb
