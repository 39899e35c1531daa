#include "app/kiosk/gallery_store.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "app/core/atomic_file.h"
#include "app/kiosk/disk_space.h"

namespace cb {
namespace fs = std::filesystem;
namespace {

constexpr const char* kIncomingPrefix = ".incoming-";

// A folder named by six or more digits; -1 otherwise.
long entryNumber(const fs::path& path) {
  const std::string name = path.filename().string();
  if (name.size() < 6 || name.size() > 12) return -1;
  for (char c : name)
    if (c < '0' || c > '9') return -1;
  return std::stol(name);
}

long readCounter(const std::string& path) {
  std::ifstream in(path);
  long n = 0;
  if (in >> n && n >= 0) return n;
  return 0;
}

bool fsyncFile(const std::string& path, std::string* error) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0 || ::fsync(fd) != 0) {
    const int err = errno;
    if (fd >= 0) ::close(fd);
    *error = path + ": fsync: " + std::strerror(err);
    return false;
  }
  ::close(fd);
  return true;
}

}  // namespace

long GalleryStore::lastNumber() const {
  long last = readCounter(dir_ + "/last-number");
  for (const GalleryEntry& e : entries()) last = std::max(last, e.number);
  return last;
}

bool GalleryStore::begin(GalleryWrite* write, std::string* error) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) {
    *error = dir_ + ": " + ec.message();
    return false;
  }
  const long next = lastNumber() + 1;
  char name[32];
  std::snprintf(name, sizeof name, "%06ld", next);
  write->number = next;
  write->final_dir = dir_ + "/" + name;
  write->temp_dir = dir_ + "/" + kIncomingPrefix + name;
  fs::remove_all(write->temp_dir, ec);
  if (!fs::create_directory(write->temp_dir, ec) || ec) {
    *error = write->temp_dir + ": " + (ec ? ec.message() : "already exists");
    return false;
  }
  return true;
}

bool GalleryStore::commit(const GalleryWrite& write, std::string* error) {
  std::error_code ec;
  bool ok = true;
  for (const auto& file : fs::directory_iterator(write.temp_dir, ec))
    if (ok && file.is_regular_file(ec)) ok = fsyncFile(file.path().string(), error);
  if (ec) *error = write.temp_dir + ": " + ec.message();
  ok = ok && !ec && syncFolderOf(write.temp_dir + "/.", error);
  if (ok && ::rename(write.temp_dir.c_str(), write.final_dir.c_str()) != 0) {
    *error = write.final_dir + ": rename: " + std::strerror(errno);
    ok = false;
  }
  if (!ok) {
    abandon(write);
    return false;
  }
  // The entry is in place; a counter that cannot be written is caught up by begin() (it also
  // counts past the highest entry), so it is reported but the entry stays.
  return syncFolderOf(write.final_dir, error) &&
         writeFileAtomically(dir_ + "/last-number", std::to_string(write.number) + "\n", error);
}

void GalleryStore::abandon(const GalleryWrite& write) {
  std::error_code ec;
  fs::remove_all(write.temp_dir, ec);
}

std::vector<std::string> GalleryStore::removeIncomplete() {
  std::vector<std::string> removed;
  std::error_code ec;
  for (const auto& item : fs::directory_iterator(dir_, ec)) {
    if (item.path().filename().string().rfind(kIncomingPrefix, 0) != 0) continue;
    std::error_code remove_ec;
    fs::remove_all(item.path(), remove_ec);
    if (!remove_ec) removed.push_back(item.path().string());
  }
  return removed;
}

std::vector<GalleryEntry> GalleryStore::entries() const {
  std::vector<GalleryEntry> out;
  std::error_code ec;
  for (const auto& item : fs::directory_iterator(dir_, ec)) {
    const long number = entryNumber(item.path());
    if (number < 0 || !item.is_directory(ec)) continue;
    GalleryEntry entry;
    entry.number = number;
    entry.path = item.path().string();
    entry.written = item.last_write_time(ec);
    for (const auto& file : fs::recursive_directory_iterator(item.path(), ec)) {
      if (!file.is_regular_file(ec)) continue;
      entry.bytes += file.file_size(ec);
      entry.written = std::max(entry.written, file.last_write_time(ec));
    }
    out.push_back(entry);
  }
  std::sort(out.begin(), out.end(),
            [](const GalleryEntry& a, const GalleryEntry& b) { return a.number < b.number; });
  return out;
}

uint64_t GalleryStore::typicalEntryBytes() const {
  const std::vector<GalleryEntry> list = entries();
  return list.empty() ? 0 : list.back().bytes;
}

bool GalleryStore::removeEntry(const GalleryEntry& entry, std::string* error) {
  std::error_code ec;
  fs::remove_all(entry.path, ec);
  if (ec && error->empty()) *error = entry.path + ": " + ec.message();
  return !ec;
}

GalleryRoom GalleryStore::makeRoom(uint64_t need_bytes, long keep, std::string* error) {
  GalleryRoom room;
  std::error_code ec;
  fs::create_directories(dir_, ec);
  const std::string measured_at = ec ? fs::path(dir_).parent_path().string() : dir_;
  std::vector<GalleryEntry> list = entries();
  auto next = list.begin();
  for (;;) {
    std::string statvfs_error;
    const std::optional<DiskSpace> disk = diskSpaceAt(measured_at, &statvfs_error);
    if (!disk) {
      if (error->empty()) *error = statvfs_error;
      room.free_bytes.reset();
      return room;
    }
    room.free_bytes = disk->free_bytes;
    room.enough = disk->free_bytes >= min_free_bytes_ + need_bytes;
    while (next != list.end() && next->number == keep) ++next;
    if (room.enough || next == list.end()) return room;
    if (removeEntry(*next, error)) room.removed.push_back(next->number);
    ++next;
  }
}

GalleryCleanup GalleryStore::enforce(long keep, fs::file_time_type now, std::string* error) {
  GalleryCleanup cleanup;
  std::vector<GalleryEntry> list = entries();
  const auto max_age = std::chrono::duration_cast<fs::file_time_type::duration>(
      std::chrono::duration<double>(keep_days_ * 86400.0));
  std::vector<GalleryEntry> kept;
  for (const GalleryEntry& e : list) {
    if (e.number != keep && now - e.written > max_age && removeEntry(e, error))
      cleanup.removed_for_age.push_back(e.number);
    else
      kept.push_back(e);
  }
  uint64_t total = 0;
  for (const GalleryEntry& e : kept) total += e.bytes;
  for (const GalleryEntry& e : kept) {  // oldest (lowest number) first
    if (total <= quota_bytes_) break;
    if (e.number == keep) continue;
    if (removeEntry(e, error)) {
      cleanup.removed_for_quota.push_back(e.number);
      total -= e.bytes;
    }
  }
  if (min_free_bytes_ > 0) {
    const GalleryRoom room = makeRoom(0, keep, error);
    cleanup.removed_for_space = room.removed;
    for (const GalleryEntry& e : kept)
      if (std::find(room.removed.begin(), room.removed.end(), e.number) != room.removed.end())
        total -= e.bytes;
  }
  cleanup.bytes_after = total;
  return cleanup;
}

}  // namespace cb
