// codebook.csv (app/study/codebook.h) of the bundled thesis protocol: a row for every
// questionnaire item with its statement in both languages, its scale and anchors, construct and
// section; a row with type, unit and meaning for every column the trial and pen-trace writers
// emit (their headers read from the writers themselves); the file reads back as CSV with one
// row per variable.
#include <gtest/gtest.h>

#include <map>
#include <sstream>

#include "app/study/bids_behaviour.h"
#include "app/study/bids_motion.h"
#include "app/study/codebook.h"
#include "app/study/export_columns.h"
#include "app/study/protocol.h"
#include "app/study/trace_csv.h"
#include "app/study/trial_table.h"

namespace cb {
namespace {

// RFC 4180 records (quoted fields may hold commas, quotes and newlines).
std::vector<std::vector<std::string>> parseCsv(const std::string& text) {
  std::vector<std::vector<std::string>> rows(1, std::vector<std::string>(1));
  bool quoted = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"')
        rows.back().back() += '"', ++i;
      else if (c == '"')
        quoted = false;
      else
        rows.back().back() += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      rows.back().emplace_back();
    } else if (c == '\n') {
      rows.emplace_back(1);
    } else {
      rows.back().back() += c;
    }
  }
  if (rows.back().size() == 1 && rows.back()[0].empty()) rows.pop_back();
  return rows;
}

struct Codebook {
  std::vector<std::string> header;
  std::map<std::string, std::map<std::string, std::string>> rows;  // "file/variable" → fields
  size_t count = 0;
};

Codebook readCodebook(const StudyProtocol& protocol) {
  std::ostringstream out;
  writeCodebookCsv(out, studyCodebook(protocol));
  const std::vector<std::vector<std::string>> csv = parseCsv(out.str());
  Codebook book;
  book.header = csv.at(0);
  for (size_t r = 1; r < csv.size(); ++r) {
    EXPECT_EQ(csv[r].size(), book.header.size()) << "row " << r;
    std::map<std::string, std::string> fields;
    for (size_t c = 0; c < csv[r].size() && c < book.header.size(); ++c)
      fields[book.header[c]] = csv[r][c];
    book.rows[fields["file"] + "/" + fields["variable"]] = fields;
    ++book.count;
  }
  return book;
}

TEST(Codebook, EveryItemOfTheBundledProtocolWithBothLanguagesScaleAndConstruct) {
  const StudyProtocol p = loadStudyProtocol(defaultStudyProtocolPath());
  ASSERT_EQ(p.items.size(), 28u);
  const Codebook book = readCodebook(p);
  EXPECT_EQ(book.count, book.rows.size()) << "no variable twice";
  for (const QuestionnaireItem& item : p.items) {
    const auto it = book.rows.find("questionnaire.csv/" + item.id);
    ASSERT_NE(it, book.rows.end()) << item.id;
    const auto& row = it->second;
    EXPECT_EQ(row.at("text_en"), item.text) << item.id;
    EXPECT_FALSE(item.text_zh.empty()) << item.id << ": the bundled items are in both languages";
    EXPECT_EQ(row.at("text_zh"), item.text_zh) << item.id;
    EXPECT_EQ(row.at("scale_min"), "1") << item.id;
    EXPECT_EQ(row.at("scale_max"), "5") << item.id;
    EXPECT_EQ(row.at("section"), item.section) << item.id;
    for (size_t k = 0; k < p.scale_labels.size(); ++k)
      EXPECT_NE(row.at("anchors").find(std::to_string(k + 1) + "=" + p.scale_labels[k] + " / " +
                                       p.scale_labels_zh.at(k)),
                std::string::npos)
          << item.id << ": " << row.at("anchors");
    EXPECT_NE(row.at("construct"), "NA") << item.id << ": every bundled item is in a construct";
  }
  // The constructs as the protocol file declares them (config/study/thesis_2014.toml).
  EXPECT_EQ(book.rows.at("questionnaire.csv/Q3").at("construct"), "Paint style");
  EXPECT_EQ(book.rows.at("questionnaire.csv/Q12").at("construct"), "Cloud drawing");
  EXPECT_NE(book.rows.at("questionnaire.csv/Q28").at("construct").find("Lag"), std::string::npos)
      << book.rows.at("questionnaire.csv/Q28").at("construct");
  // Demographic fields: the age's allowed range.
  EXPECT_EQ(book.rows.at("demographics.csv/age").at("scale_min"), "16");
  EXPECT_EQ(book.rows.at("demographics.csv/age").at("scale_max"), "99");
}

TEST(Codebook, EveryColumnTheWritersEmitHasATypeAUnitAndAMeaning) {
  const StudyProtocol p = loadStudyProtocol(defaultStudyProtocolPath());
  const Codebook book = readCodebook(p);
  const std::pair<const char*, void (*)(std::ostream&)> writers[] = {
      {"trials.csv", writeTrialsCsvHeader},
      {"strokes.csv", writeStrokesCsvHeader},
      {"samples.csv", writeSamplesCsvHeader},
      {"events.csv", writeEventsCsvHeader}};
  size_t columns = 0;
  for (const auto& [file, write] : writers) {
    std::ostringstream header;
    write(header);
    const std::vector<std::vector<std::string>> csv = parseCsv(header.str());
    ASSERT_EQ(csv.size(), 1u) << file;
    for (const std::string& column : csv[0]) {
      ++columns;
      const auto it = book.rows.find(std::string(file) + "/" + column);
      ASSERT_NE(it, book.rows.end()) << file << " column " << column << " is not in the codebook";
      EXPECT_NE(it->second.at("meaning"), "NA") << file << " " << column << ": no meaning";
      EXPECT_NE(it->second.at("type"), "NA") << file << " " << column << ": no type";
      // A measured number carries the unit its name says; counts and ids may have none.
      const std::string unit = it->second.at("unit");
      const auto ends = [&](const std::string& tail) {
        return column.size() > tail.size() &&
               column.compare(column.size() - tail.size(), tail.size(), tail) == 0;
      };
      if (ends("_mm_s")) {
        EXPECT_EQ(unit, "mm/s") << file << " " << column;
      } else if (ends("_s")) {
        EXPECT_EQ(unit, "s") << file << " " << column;
      }
      if (ends("_ns")) {
        EXPECT_EQ(unit, "ns") << file << " " << column;
      }
      if (ends("_ms")) {
        EXPECT_EQ(unit, "ms") << file << " " << column;
      }
      if (ends("_mm")) {
        EXPECT_EQ(unit, "mm") << file << " " << column;
      }
      if (ends("_deg")) {
        EXPECT_EQ(unit, "deg") << file << " " << column;
      }
    }
  }
  EXPECT_GT(columns, 50u) << "the four tables' headers were read";
  // csvHeaderColumns reads a writer's header the same way.
  EXPECT_EQ(csvHeaderColumns(writeTrialsCsvHeader).front(), "participant");
  EXPECT_EQ(csvHeaderColumns(writeTrialsCsvHeader).back(), "undos");
}

TEST(Codebook, AProtocolWithoutChineseTextsLeavesThemNA) {
  StudyProtocol p = loadStudyProtocol(defaultStudyProtocolPath());
  for (QuestionnaireItem& item : p.items) item.text_zh.clear();
  p.scale_labels_zh.clear();
  const Codebook book = readCodebook(p);
  EXPECT_EQ(book.rows.at("questionnaire.csv/Q1").at("text_zh"), "NA");
  EXPECT_EQ(book.rows.at("questionnaire.csv/Q1").at("anchors").find(" / "), std::string::npos);
}

size_t countOf(const std::string& text, const std::string& needle) {
  size_t n = 0;
  for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
  return n;
}

size_t entriesNamed(const std::vector<ExportColumn>& table, const std::string& name) {
  size_t n = 0;
  for (const ExportColumn& c : table) n += c.name == name;
  return n;
}

std::vector<std::string> tsvHeader(const std::string& tsv) {
  std::vector<std::string> names(1);
  for (char c : tsv.substr(0, tsv.find('\n'))) {
    if (c == '\t')
      names.emplace_back();
    else
      names.back() += c;
  }
  return names;
}

// One table of column meanings (export_columns.h): every column a CSV writer or a BIDS file
// emits has exactly one entry there, with a description, and exactly one row in the codebook
// and one key in its sidecar; nothing is described that is not exported.
TEST(ExportColumns, EveryExportedColumnHasExactlyOneEntry) {
  const StudyProtocol p = loadStudyProtocol(defaultStudyProtocolPath());
  std::map<std::string, size_t> codebook_rows;  // "file/variable" → rows
  for (const CodebookRow& row : studyCodebook(p)) ++codebook_rows[row.file + "/" + row.variable];
  const struct {
    const char* file;
    void (*write_header)(std::ostream&);
    const std::vector<ExportColumn>& table;
  } csvs[] = {{"trials.csv", writeTrialsCsvHeader, trialColumns()},
              {"strokes.csv", writeStrokesCsvHeader, strokeColumns()},
              {"samples.csv", writeSamplesCsvHeader, sampleColumns()},
              {"events.csv", writeEventsCsvHeader, eventColumns()}};
  for (const auto& csv : csvs) {
    const std::vector<std::string> header = csvHeaderColumns(csv.write_header);
    EXPECT_EQ(header.size(), csv.table.size()) << csv.file << ": a column without an entry";
    for (const std::string& column : header) {
      EXPECT_EQ(entriesNamed(csv.table, column), 1u) << csv.file << " " << column;
      EXPECT_EQ(codebook_rows[std::string(csv.file) + "/" + column], 1u)
          << csv.file << " " << column;
      EXPECT_FALSE(exportColumn(csv.table, column).description.empty()) << column;
    }
  }
  // BIDS: beh.tsv is trials.csv; events.tsv has its own table; each sidecar key once.
  const SessionTrace empty;
  const std::pair<std::vector<std::string>, std::string> bids[] = {
      {tsvHeader(bidsBehTsv(empty)), bidsBehJson()},
      {tsvHeader(bidsEventsTsv(empty)), bidsEventsJson()}};
  EXPECT_EQ(bids[0].first, csvHeaderColumns(writeTrialsCsvHeader));
  for (const auto& [header, json] : bids) {
    EXPECT_EQ(countOf(json, "\": {\"Description\""), header.size()) << json;
    for (const std::string& column : header)
      EXPECT_EQ(countOf(json, "\"" + column + "\": {\"Description\""), 1u) << column;
  }
  for (const std::string& column : bids[1].first)
    EXPECT_EQ(entriesNamed(bidsEventColumns(), column), 1u) << "events.tsv " << column;
  // The motion channels: each carries one samples.csv column and is described by its entry.
  const std::string channels = bidsChannelsTsv();
  std::istringstream lines(channels);
  std::string line;
  std::getline(lines, line);  // header
  size_t rows = 0;
  while (std::getline(lines, line)) {
    ++rows;
    const size_t at = line.find("(samples.csv: ");
    ASSERT_NE(at, std::string::npos) << line;
    const std::string column = line.substr(at + 14, line.find(')', at) - at - 14);
    ASSERT_EQ(entriesNamed(sampleColumns(), column), 1u) << line;
    std::string description = exportColumn(sampleColumns(), column).description;
    EXPECT_NE(line.find(description.substr(0, 30)), std::string::npos) << line;
  }
  EXPECT_EQ(rows, 11u) << channels;
}

}  // namespace
}  // namespace cb
