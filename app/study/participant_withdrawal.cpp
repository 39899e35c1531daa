#include "app/study/participant_withdrawal.h"

#include <cctype>
#include <fstream>
#include <sstream>
#include <system_error>

#include "app/core/atomic_file.h"
#include "app/study/likert_answers.h"  // splitCsvLine

namespace cb {
namespace {

namespace fs = std::filesystem;

bool validId(const std::string& id) {
  if (id.empty() || id.size() > 64) return false;
  for (char c : id)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) return false;
  return true;
}

// ID itself, or ID followed by a separator.
bool namedFor(const std::string& name, const std::string& id) {
  if (name.compare(0, id.size(), id) != 0) return false;
  return name.size() == id.size() || name[id.size()] == '_' || name[id.size()] == '-' ||
         name[id.size()] == '.';
}

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw WithdrawalError(path.string() + ": cannot read");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

struct CsvPlan {
  fs::path file;
  std::string kept;  // the rewritten text
  int removed = 0;
};

// The rows of `path` that belong to `id`; none when the file has no participant/session column.
CsvPlan planCsv(const fs::path& path, const std::string& id) {
  CsvPlan plan{path, "", 0};
  const std::string text = readAll(path);
  std::istringstream in(text);
  std::string line;
  int line_number = 0;
  int participant_column = -1, session_column = -1;
  std::vector<std::string> fields;
  while (std::getline(in, line)) {
    ++line_number;
    const bool had_newline = !in.eof();
    std::string record = line;
    if (!record.empty() && record.back() == '\r') record.pop_back();
    if (!splitCsvLine(record, &fields))
      throw WithdrawalError(path.string() + ":" + std::to_string(line_number) +
                            ": unclosed quote; not rewriting this file (nothing was deleted)");
    bool drop = false;
    if (line_number == 1) {
      for (size_t i = 0; i < fields.size(); ++i) {
        if (fields[i] == "participant") participant_column = int(i);
        if (fields[i] == "session") session_column = int(i);
      }
    } else {
      drop = (participant_column >= 0 && size_t(participant_column) < fields.size() &&
              fields[size_t(participant_column)] == id) ||
             (session_column >= 0 && size_t(session_column) < fields.size() &&
              namedFor(fields[size_t(session_column)], id));
    }
    if (drop) {
      ++plan.removed;
    } else {
      plan.kept += line;
      if (had_newline) plan.kept += '\n';
    }
  }
  return plan;
}

void replaceFile(const fs::path& path, const std::string& text) {
  std::string error;
  if (!writeFileAtomically(path.string(), text, &error))
    throw WithdrawalError(path.string() + ": cannot replace: " + error);
}

bool mentionsId(const fs::path& path, const std::string& id) {
  std::error_code ec;
  if (fs::file_size(path, ec) > (64u << 20) || ec) return false;
  const std::string text = readAll(path);
  for (size_t at = text.find(id); at != std::string::npos; at = text.find(id, at + 1)) {
    const auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0; };
    const bool starts = at == 0 || !word(text[at - 1]);
    const bool ends = at + id.size() == text.size() || !word(text[at + id.size()]);
    if (starts && ends) return true;
  }
  return false;
}

}  // namespace

WithdrawalResult withdrawParticipant(const fs::path& data_dir, const std::string& participant,
                                     const fs::path& key_file, bool dry_run) {
  if (!validId(participant))
    throw WithdrawalError("'" + participant +
                          "' is not a participant id (letters, digits, '_' and '-' only)");
  std::error_code ec;
  if (!fs::is_directory(data_dir, ec))
    throw WithdrawalError(data_dir.string() + ": not a directory");

  // Plan everything first: a file that cannot be handled stops the withdrawal untouched.
  std::vector<fs::path> paths;
  std::vector<CsvPlan> csv_plans;
  for (auto it = fs::recursive_directory_iterator(data_dir);
       it != fs::recursive_directory_iterator(); ++it) {
    const fs::path& path = it->path();
    if (namedFor(path.filename().string(), participant)) {
      paths.push_back(path);
      if (it->is_directory() && !it->is_symlink()) it.disable_recursion_pending();
      continue;
    }
    if (it->is_regular_file() && path.extension() == ".csv") {
      CsvPlan plan = planCsv(path, participant);
      if (plan.removed > 0) csv_plans.push_back(std::move(plan));
    }
  }
  if (!key_file.empty()) {
    if (!fs::is_regular_file(key_file, ec))
      throw WithdrawalError(key_file.string() + ": key file not found");
    CsvPlan plan = planCsv(key_file, participant);
    if (plan.removed > 0) csv_plans.push_back(std::move(plan));
  }
  if (paths.empty() && csv_plans.empty())
    throw WithdrawalError(
        "participant '" + participant + "' matches nothing under " + data_dir.string() +
        (key_file.empty() ? "" : " or in " + key_file.string()) + "; nothing deleted");

  WithdrawalResult result;
  result.removed_paths = paths;
  for (const CsvPlan& plan : csv_plans) result.removed_rows.push_back({plan.file, plan.removed});
  if (dry_run) return result;
  for (const fs::path& path : paths) {
    fs::remove_all(path, ec);
    if (ec) throw WithdrawalError(path.string() + ": cannot delete: " + ec.message());
  }
  for (const CsvPlan& plan : csv_plans) replaceFile(plan.file, plan.kept);

  for (auto it = fs::recursive_directory_iterator(data_dir);
       it != fs::recursive_directory_iterator(); ++it)
    if (it->is_regular_file() && mentionsId(it->path(), participant))
      result.still_mentioning.push_back(it->path());
  return result;
}

}  // namespace cb
