// The kiosk's gallery on disk (issue 11): each visitor's finished cloud in its own folder
// <gallery dir>/NNNNNN named by a pseudonymous sequential number (no names, no times in the
// name; the counter lives in <gallery dir>/last-number and never goes back, so numbers are not
// reused after a cleanup). A disk quota and a retention time are kept by deleting whole entries,
// oldest (lowest number) first. Files only: what goes into an entry is the caller's.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace cb {

struct GalleryEntry {
  long number = 0;
  std::string path;
  uint64_t bytes = 0;
  std::filesystem::file_time_type written;  // the newest file's time
};

struct GalleryCleanup {
  std::vector<long> removed_for_quota, removed_for_age;
  uint64_t bytes_after = 0;
};

class GalleryStore {
 public:
  GalleryStore(std::string dir, uint64_t quota_bytes, double keep_days)
      : dir_(std::move(dir)), quota_bytes_(quota_bytes), keep_days_(keep_days) {}
  const std::string& dir() const { return dir_; }
  double keepDays() const { return keep_days_; }

  // Creates the next entry's folder; false with *error naming the path.
  bool allocate(long* number, std::string* path, std::string* error);
  // Entries in number order.
  std::vector<GalleryEntry> entries() const;
  // Deletes entries older than keep_days at `now`, then the oldest until the total fits the
  // quota; never `keep` (the entry just written). Errors are collected in *error (first one).
  GalleryCleanup enforce(long keep, std::filesystem::file_time_type now, std::string* error);

 private:
  std::string dir_;
  uint64_t quota_bytes_;
  double keep_days_;
};

}  // namespace cb
