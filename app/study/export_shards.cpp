#include "app/study/export_shards.h"

#include <charconv>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace cb {
namespace {

std::string trimmed(const std::string& text) {
  const size_t first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

// A whole decimal number in [low, high]; false for anything else (signs, spaces, overflow).
bool parseCount(const std::string& text, long long low, long long high, long long* value) {
  if (text.empty() || text.size() > 18) return false;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, *value);
  return ec == std::errc() && ptr == end && *value >= low && *value <= high;
}

[[noreturn]] void refuse(const std::string& name, int line, const std::string& what) {
  throw StudyInputError(name + ":" + std::to_string(line) + ": " + what);
}

}  // namespace

std::vector<std::string> parseExportManifest(std::istream& in, const std::string& name,
                                             const std::string& base_dir, bool check_files_exist) {
  std::vector<std::string> journals;
  std::string raw;
  for (int line = 1; std::getline(in, raw); ++line) {
    const std::string text = trimmed(raw);
    if (text.empty() || text[0] == '#') continue;
    for (unsigned char c : text)
      if (c < 0x20 || c == 0x7f) refuse(name, line, "journal: a control byte in the path");
    std::filesystem::path path(text);
    if (path.is_relative() && !base_dir.empty()) path = std::filesystem::path(base_dir) / path;
    if (check_files_exist && !std::filesystem::is_regular_file(path))
      refuse(name, line, "journal: '" + path.string() + "' does not exist or is not a file");
    journals.push_back(path.string());
  }
  if (journals.empty()) refuse(name, 1, "journal: the manifest lists no journals");
  return journals;
}

std::vector<std::string> readExportManifest(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw StudyInputError(path + ": cannot read the manifest");
  return parseExportManifest(in, path, std::filesystem::path(path).parent_path().string());
}

bool parseShardSpec(const std::string& text, ShardSpec* spec, std::string* error) {
  const size_t slash = text.find('/');
  long long index = 0, count = 0;
  if (slash == std::string::npos || !parseCount(text.substr(slash + 1), 1, kMaxShards, &count) ||
      !parseCount(text.substr(0, slash), 1, count, &index)) {
    *error = "--shard: expected I/N with 1 <= I <= N <= " + std::to_string(kMaxShards) + ", got '" +
             text + "'";
    return false;
  }
  spec->index = int(index);
  spec->count = int(count);
  return true;
}

SessionRange shardRange(size_t sessions, const ShardSpec& spec) {
  const size_t n = size_t(spec.count), i = size_t(spec.index - 1);
  return {sessions * i / n, sessions * (i + 1) / n};
}

std::string shardFolder(const std::string& out, const ShardSpec& spec) {
  return (std::filesystem::path(out) / "shards" /
          (std::to_string(spec.index) + "-of-" + std::to_string(spec.count)))
      .string();
}

std::string shardRecordText(const ShardRecord& record) {
  std::ostringstream out;
  out << "shard " << record.spec.index << "/" << record.spec.count << "\n";
  out << "sessions " << record.sessions.begin << " " << record.sessions.end << "\n";
  for (const std::string& id : record.session_ids) out << "id " << id << "\n";
  out << "protocol " << record.protocol << "\n";
  for (const std::string& path : record.damaged) out << "damaged " << path << "\n";
  out << "end\n";
  return out.str();
}

ShardRecord parseShardRecord(const std::string& text, const std::string& name) {
  ShardRecord record;
  std::istringstream in(text);
  std::string raw;
  bool have_shard = false, have_sessions = false, have_end = false;
  int line = 0;
  while (std::getline(in, raw)) {
    ++line;
    if (have_end) refuse(name, line, "end: lines after the end");
    const size_t space = raw.find(' ');
    const std::string key = raw.substr(0, space);
    const std::string value = space == std::string::npos ? "" : raw.substr(space + 1);
    if (key == "shard") {
      std::string error;
      if (!parseShardSpec(value, &record.spec, &error)) refuse(name, line, "shard: " + error);
      have_shard = true;
    } else if (key == "sessions") {
      const size_t gap = value.find(' ');
      long long begin = 0, end = 0;
      if (gap == std::string::npos || !parseCount(value.substr(0, gap), 0, 1LL << 40, &begin) ||
          !parseCount(value.substr(gap + 1), begin, 1LL << 40, &end))
        refuse(name, line, "sessions: expected BEGIN END with BEGIN <= END");
      record.sessions = {size_t(begin), size_t(end)};
      have_sessions = true;
    } else if (key == "id") {
      record.session_ids.push_back(value);
    } else if (key == "protocol") {
      record.protocol = value;
    } else if (key == "damaged") {
      record.damaged.push_back(value);
    } else if (key == "end" && value.empty()) {
      have_end = true;
    } else {
      refuse(name, line, "'" + key + "': not a field of a shard record");
    }
  }
  if (!have_shard || !have_sessions || !have_end)
    refuse(name, line,
           std::string(!have_shard      ? "shard"
                       : !have_sessions ? "sessions"
                                        : "end") +
               ": missing (the shard did not finish)");
  if (record.session_ids.size() != record.sessions.end - record.sessions.begin)
    refuse(name, line,
           "id: " + std::to_string(record.session_ids.size()) + " ids for " +
               std::to_string(record.sessions.end - record.sessions.begin) + " sessions");
  return record;
}

}  // namespace cb
