#include "app/study/bids_text.h"

#include <cctype>
#include <cmath>

#include "app/core/json_text.h"
#include "app/study/csv_text.h"
#include "app/study/utf8_text.h"

namespace cb {

std::string bidsMissingWords(const std::string& text) {
  std::string out;
  const auto word = [&](size_t i) {
    return i < text.size() && std::isalnum(static_cast<unsigned char>(text[i]));
  };
  for (size_t i = 0; i < text.size(); ++i) {
    if (text.compare(i, 2, "NA") == 0 && (i == 0 || !word(i - 1)) && !word(i + 2)) {
      out += kBidsMissing;
      ++i;
    } else {
      out += text[i];
    }
  }
  return out;
}

std::vector<BidsColumn> bidsColumnsOf(const std::vector<ExportColumn>& table) {
  std::vector<BidsColumn> columns;
  for (const ExportColumn& c : table)
    columns.push_back({c.name, bidsMissingWords(c.description), bidsUnit(c.unit), c.levels});
  return columns;
}

std::string bidsTsvHeader(const std::vector<BidsColumn>& columns) {
  std::string out;
  for (size_t i = 0; i < columns.size(); ++i) out += (i ? "\t" : "") + columns[i].name;
  return out + '\n';
}

std::string bidsColumnsJson(const std::vector<BidsColumn>& columns) {
  std::vector<std::pair<std::string, std::string>> members;
  for (const BidsColumn& c : columns) {
    std::string body = "{\"Description\": " + jsonString(c.description);
    if (!c.units.empty()) body += ", \"Units\": " + jsonString(c.units);
    if (!c.levels.empty()) {
      body += ", \"Levels\": {";
      for (size_t i = 0; i < c.levels.size(); ++i)
        body +=
            (i ? ", " : "") + jsonString(c.levels[i].first) + ": " + jsonString(c.levels[i].second);
      body += "}";
    }
    members.emplace_back(c.name, body + "}");
  }
  return bidsJsonObject(members);
}

std::string bidsTsvText(const std::string& text) {
  if (text.empty()) return kBidsMissing;
  std::string out = validUtf8(text);
  for (char& c : out)
    if (c == '\t' || c == '\n' || c == '\r') c = ' ';
  return out;
}

std::string bidsTsvNumber(const std::optional<double>& value) {
  return value && std::isfinite(*value) ? csvDouble(*value) : std::string(kBidsMissing);
}

std::string bidsSeconds(int64_t ns) {
  return decimalSecondsFromNs(ns);
}

std::string bidsLabel(const std::string& text) {
  std::string out;
  for (char c : text)
    if (std::isalnum(static_cast<unsigned char>(c))) out += c;
  return out;
}

std::string bidsJsonObject(const std::vector<std::pair<std::string, std::string>>& members) {
  std::string out = "{\n";
  for (size_t i = 0; i < members.size(); ++i)
    out += "  " + jsonString(members[i].first) + ": " + members[i].second +
           (i + 1 < members.size() ? ",\n" : "\n");
  return out + "}\n";
}

}  // namespace cb
