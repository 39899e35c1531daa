#include "app/kiosk/gallery_store.h"

#include <algorithm>
#include <cstdio>
#include <fstream>

#include "app/kiosk/atomic_file.h"

namespace cb {
namespace fs = std::filesystem;
namespace {

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

}  // namespace

bool GalleryStore::allocate(long* number, std::string* path, std::string* error) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) {
    *error = dir_ + ": " + ec.message();
    return false;
  }
  long next = readCounter(dir_ + "/last-number") + 1;
  for (const GalleryEntry& e : entries()) next = std::max(next, e.number + 1);
  char name[32];
  std::snprintf(name, sizeof name, "%06ld", next);
  *path = dir_ + "/" + name;
  if (!fs::create_directory(*path, ec) || ec) {
    *error = *path + ": " + (ec ? ec.message() : "already exists");
    return false;
  }
  if (!writeFileAtomically(dir_ + "/last-number", std::to_string(next) + "\n", error)) return false;
  *number = next;
  return true;
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

GalleryCleanup GalleryStore::enforce(long keep, fs::file_time_type now, std::string* error) {
  GalleryCleanup cleanup;
  std::vector<GalleryEntry> list = entries();
  const auto max_age = std::chrono::duration_cast<fs::file_time_type::duration>(
      std::chrono::duration<double>(keep_days_ * 86400.0));
  const auto remove = [&](const GalleryEntry& e) {
    std::error_code ec;
    fs::remove_all(e.path, ec);
    if (ec && error->empty()) *error = e.path + ": " + ec.message();
    return !ec;
  };
  std::vector<GalleryEntry> kept;
  for (const GalleryEntry& e : list) {
    if (e.number != keep && now - e.written > max_age && remove(e))
      cleanup.removed_for_age.push_back(e.number);
    else
      kept.push_back(e);
  }
  uint64_t total = 0;
  for (const GalleryEntry& e : kept) total += e.bytes;
  for (const GalleryEntry& e : kept) {  // oldest (lowest number) first
    if (total <= quota_bytes_) break;
    if (e.number == keep) continue;
    if (remove(e)) {
      cleanup.removed_for_quota.push_back(e.number);
      total -= e.bytes;
    }
  }
  cleanup.bytes_after = total;
  return cleanup;
}

}  // namespace cb
