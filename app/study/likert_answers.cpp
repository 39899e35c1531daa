#include "app/study/likert_answers.h"

#include <charconv>
#include <fstream>
#include <set>

namespace cb {

int LikertAnswers::itemIndex(const std::string& id) const {
  for (size_t i = 0; i < items.size(); ++i)
    if (items[i] == id) return int(i);
  return -1;
}

std::vector<int> LikertAnswers::itemValues(size_t i) const {
  std::vector<int> values;
  for (const auto& row : answers)
    if (row[i]) values.push_back(*row[i]);
  return values;
}

bool splitCsvLine(const std::string& line, std::vector<std::string>* fields) {
  fields->clear();
  std::string field;
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields->push_back(field);
      field.clear();
    } else {
      field += c;
    }
  }
  if (quoted) return false;
  fields->push_back(field);
  return true;
}

namespace {

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const size_t b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

}  // namespace

LikertAnswers readLikertAnswers(std::istream& in, const std::string& name, int scale_min,
                                int scale_max) {
  LikertAnswers result;
  result.scale_min = scale_min;
  result.scale_max = scale_max;
  std::string line;
  size_t line_no = 0;
  std::vector<std::string> fields;
  const auto where = [&](size_t column) {
    return name + ": line " + std::to_string(line_no) +
           (column ? ", column " + std::to_string(column) : std::string()) + ": ";
  };
  bool have_header = false;
  std::set<std::string> seen_participants;
  while (std::getline(in, line)) {
    ++line_no;
    if (trim(line).empty()) continue;
    if (!splitCsvLine(line, &fields)) throw StudyInputError(where(0) + "unclosed quote");
    for (std::string& f : fields) f = trim(f);
    if (!have_header) {
      if (fields.size() < 2)
        throw StudyInputError(where(0) +
                              "the header needs a participant column and at least one "
                              "item column");
      std::set<std::string> seen;
      for (size_t c = 1; c < fields.size(); ++c) {
        if (fields[c].empty()) throw StudyInputError(where(c + 1) + "empty item name");
        if (!seen.insert(fields[c]).second)
          throw StudyInputError(where(c + 1) + "item '" + fields[c] + "' appears twice");
        result.items.push_back(fields[c]);
      }
      have_header = true;
      continue;
    }
    if (fields.size() != result.items.size() + 1)
      throw StudyInputError(where(0) + "expected " + std::to_string(result.items.size() + 1) +
                            " fields (participant and " + std::to_string(result.items.size()) +
                            " items), found " + std::to_string(fields.size()));
    if (fields[0].empty()) throw StudyInputError(where(1) + "participant: empty");
    if (!seen_participants.insert(fields[0]).second)
      throw StudyInputError(where(1) + "participant '" + fields[0] + "' appears twice");
    result.participants.push_back(fields[0]);
    std::vector<std::optional<int>> row;
    for (size_t c = 1; c < fields.size(); ++c) {
      const std::string& f = fields[c];
      if (f.empty() || f == "NA") {
        row.push_back(std::nullopt);
        continue;
      }
      int v = 0;
      const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
      if (ec != std::errc() || end != f.data() + f.size() || v < scale_min || v > scale_max)
        throw StudyInputError(where(c + 1) + result.items[c - 1] + ": '" + f +
                              "' is not an answer (expected an integer " +
                              std::to_string(scale_min) + ".." + std::to_string(scale_max) +
                              " or NA)");
      row.push_back(v);
    }
    result.answers.push_back(std::move(row));
  }
  if (!have_header) throw StudyInputError(name + ": no header line (empty file)");
  return result;
}

LikertAnswers loadLikertAnswers(const std::string& path, int scale_min, int scale_max) {
  std::ifstream in(path);
  if (!in) throw StudyInputError(path + ": cannot open");
  return readLikertAnswers(in, path, scale_min, scale_max);
}

}  // namespace cb
