// The kiosk's gallery on disk: each visitor's finished cloud in its own folder
// <gallery dir>/NNNNNN named by a pseudonymous sequential number (no names, no times in the
// name; the counter lives in <gallery dir>/last-number and never goes back, so numbers are not
// reused after a cleanup). An entry is written into <gallery dir>/.incoming-NNNNNN, its files
// fsynced, then renamed into place (and the folder fsynced): a reader, or the kiosk after a
// crash or a full disk, sees a whole entry or none. Whole entries are deleted, oldest (lowest
// number) first, to keep a floor of free space on the file system (statvfs, not the gallery's
// own sum: journals, logs and other programs fill the same disk), a quota of the gallery's own
// bytes and a retention time. Files only: what goes into an entry is the caller's.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
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
  std::vector<long> removed_for_quota, removed_for_age, removed_for_space;
  uint64_t bytes_after = 0;
};

// An entry being written: the caller writes its files into `temp_dir`, then commit() or
// abandon().
struct GalleryWrite {
  long number = 0;
  std::string temp_dir;   // <gallery dir>/.incoming-NNNNNN
  std::string final_dir;  // <gallery dir>/NNNNNN once committed
};

// Free space against the floor after makeRoom().
struct GalleryRoom {
  std::vector<long> removed;           // entries deleted to make room, oldest first
  std::optional<uint64_t> free_bytes;  // statvfs f_bavail × f_frsize; none: statvfs failed
  bool enough = false;                 // free_bytes >= floor + the bytes asked for
};

class GalleryStore {
 public:
  // `min_free_bytes`: the floor of free space on the gallery's file system (0: none).
  GalleryStore(std::string dir, uint64_t quota_bytes, double keep_days, uint64_t min_free_bytes = 0)
      : dir_(std::move(dir)),
        quota_bytes_(quota_bytes),
        keep_days_(keep_days),
        min_free_bytes_(min_free_bytes) {}
  const std::string& dir() const { return dir_; }
  double keepDays() const { return keep_days_; }
  uint64_t minFreeBytes() const { return min_free_bytes_; }

  // Creates the next entry's temporary folder; false with *error naming the path.
  bool begin(GalleryWrite* write, std::string* error);
  // fsyncs every file in the temporary folder, renames it into place, fsyncs the gallery folder
  // and records the number. On failure the temporary folder is removed: false with *error.
  bool commit(const GalleryWrite& write, std::string* error);
  // Removes the temporary folder (a failed or interrupted write).
  void abandon(const GalleryWrite& write);
  // Removes the temporary folders a killed kiosk left; their paths.
  std::vector<std::string> removeIncomplete();

  // Entries in number order (temporary folders are not entries).
  std::vector<GalleryEntry> entries() const;
  // The newest number ever given to an entry (kept in last-number, so it holds after the entry
  // was deleted); 0 before the first.
  long lastNumber() const;
  // The newest entry's bytes: what the next entry will likely need (0 without entries).
  uint64_t typicalEntryBytes() const;
  // Deletes the oldest entries (never `keep`) until the file system has the floor plus
  // `need_bytes` free, or no entry is left to delete.
  GalleryRoom makeRoom(uint64_t need_bytes, long keep, std::string* error);
  // Deletes entries older than keep_days at `now`, then the oldest until the total fits the
  // quota, then the oldest until the floor of free space holds; never `keep` (the entry just
  // written). Errors are collected in *error (first one).
  GalleryCleanup enforce(long keep, std::filesystem::file_time_type now, std::string* error);

 private:
  bool removeEntry(const GalleryEntry& entry, std::string* error);

  std::string dir_;
  uint64_t quota_bytes_;
  double keep_days_;
  uint64_t min_free_bytes_;
};

}  // namespace cb
