// Whether the runner can write to its session folder (thesis §7.5's record must survive a full
// disk or a failing drive): the outages as they begin and end, for the operator's screen and
// session.json. The runner keeps what it could not write (the journal holds its records in
// memory and writes them again, drivers/core/journal.h; the answer files and session.json are
// written again each second) and carries on when writing works again.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace cb {

struct StorageOutage {
  std::string error;              // the first error of the outage (e.g. "... No space left")
  int64_t since_unix_ns = 0;      // when it began (UTC)
  int64_t recovered_unix_ns = 0;  // when writing worked again; 0: not yet
};

class StudyStorageWatch {
 public:
  // Called once a frame with whether a write is failing now and the newest error. True when an
  // outage began or ended with this call.
  bool observe(bool failing, const std::string& error, int64_t unix_now_ns);
  bool failing() const { return !outages_.empty() && outages_.back().recovered_unix_ns == 0; }
  const std::vector<StorageOutage>& outages() const { return outages_; }
  // The operator's banner while failing ("" otherwise): what failed, since when, what is kept
  // in memory, and which files are waiting to be written (`pending_files`, "" for none).
  std::string operatorText(size_t held_bytes, int64_t unix_now_ns,
                           const std::string& pending_files = "") const;
  // session.json's "storage" object: {"status": "ok" | "failing" | "recovered", "outages":
  // [{"error", "since_utc", "recovered_utc" (null while failing)}]}.
  std::string json() const;

 private:
  std::vector<StorageOutage> outages_;
};

}  // namespace cb
