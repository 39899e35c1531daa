#include "app/study/study_storage_watch.h"

#include <ctime>

#include "app/core/json_text.h"

namespace cb {
namespace {

std::string utc(int64_t unix_ns) {
  const std::time_t seconds = std::time_t(unix_ns / 1'000'000'000);
  std::tm tm{};
  gmtime_r(&seconds, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

}  // namespace

bool StudyStorageWatch::observe(bool now_failing, const std::string& error, int64_t unix_now_ns) {
  if (now_failing == failing()) return false;
  if (now_failing)
    outages_.push_back({error, unix_now_ns, 0});
  else
    outages_.back().recovered_unix_ns = unix_now_ns;
  return true;
}

std::string StudyStorageWatch::operatorText(size_t held_bytes, int64_t unix_now_ns,
                                            const std::string& pending_files) const {
  if (!failing()) return "";
  const StorageOutage& o = outages_.back();
  const long seconds = long((unix_now_ns - o.since_unix_ns) / 1'000'000'000);
  return "OPERATOR: the session folder cannot be written for " + std::to_string(seconds) +
         " s: " + o.error + ". Nothing recorded is lost yet (" +
         std::to_string((held_bytes + 1023) / 1024) + " KiB held in memory" +
         (pending_files.empty() ? "" : "; waiting to be written: " + pending_files) +
         "); free space on the disk and the session carries on writing.";
}

std::string StudyStorageWatch::json() const {
  std::string j = "{\"status\": \"";
  j += outages_.empty() ? "ok" : failing() ? "failing" : "recovered";
  j += "\", \"outages\": [";
  for (size_t i = 0; i < outages_.size(); ++i) {
    const StorageOutage& o = outages_[i];
    j += (i ? ", " : "") + std::string("{\"error\": ") + jsonString(o.error) +
         ", \"since_utc\": \"" + utc(o.since_unix_ns) + "\", \"recovered_utc\": " +
         (o.recovered_unix_ns ? "\"" + utc(o.recovered_unix_ns) + "\"" : std::string("null")) + "}";
  }
  return j + "]}";
}

}  // namespace cb
