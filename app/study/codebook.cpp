#include "app/study/codebook.h"

#include <sstream>

#include "app/study/csv_text.h"
#include "app/study/export_columns.h"
#include "app/study/trace_csv.h"
#include "app/study/trial_table.h"

namespace cb {
namespace {

struct TableColumns {
  const char* file;
  void (*write_header)(std::ostream&);
  const std::vector<ExportColumn>& (*columns)();
};

const TableColumns kTables[] = {
    {"trials.csv", writeTrialsCsvHeader, trialColumns},
    {"strokes.csv", writeStrokesCsvHeader, strokeColumns},
    {"samples.csv", writeSamplesCsvHeader, sampleColumns},
    {"events.csv", writeEventsCsvHeader, eventColumns},
};

// The column of a table as its header names it, described by the one column table
// (export_columns.h); a column it does not know keeps an empty meaning (the test refuses it).
CodebookRow columnRow(const TableColumns& table, const std::string& column) {
  CodebookRow row;
  row.file = table.file;
  row.variable = column;
  for (const ExportColumn& c : table.columns()) {
    if (c.name != column) continue;
    row.type = c.type;
    row.unit = c.unit;
    row.meaning = c.description;
    for (const auto& [value, meaning] : c.levels)
      row.anchors += (row.anchors.empty() ? "" : "; ") + value + "=" + meaning;
  }
  return row;
}

std::string joined(const std::vector<std::string>& parts, const char* separator) {
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : separator) + p;
  return out;
}

CodebookRow variableRow(const char* file, const std::string& variable, const char* type,
                        const char* unit, const char* meaning) {
  CodebookRow row;
  row.file = file, row.variable = variable, row.type = type, row.unit = unit;
  row.meaning = meaning;
  return row;
}

void addAnswerRows(const StudyProtocol& protocol, std::vector<CodebookRow>* rows) {
  const CodebookRow participant =
      variableRow("questionnaire.csv", "participant", "text", "",
                  exportColumn(trialColumns(), "participant").description.c_str());
  rows->push_back(participant);
  std::vector<std::string> anchors;
  for (size_t k = 0; k < protocol.scale_labels.size(); ++k)
    anchors.push_back(std::to_string(k + 1) + "=" + protocol.scale_labels[k] +
                      (k < protocol.scale_labels_zh.size() ? " / " + protocol.scale_labels_zh[k]
                                                           : std::string()));
  for (const QuestionnaireItem& item : protocol.items) {
    CodebookRow row = variableRow(
        "questionnaire.csv", item.id, "integer", "points",
        "agreement with the statement text_en / text_zh (Likert; *...* marks the thesis's "
        "emphasis, shown without the marks); NA: skipped");
    row.text_en = item.text;
    row.text_zh = item.text_zh;
    row.scale_min = "1";
    row.scale_max = std::to_string(protocol.scale_labels.size());
    row.anchors = joined(anchors, "; ");
    std::vector<std::string> constructs;
    for (const ProtocolConstruct& c : protocol.constructs)
      for (const std::string& id : c.items)
        if (id == item.id) constructs.push_back(c.name);
    row.construct = joined(constructs, "; ");
    row.section = item.section;
    rows->push_back(row);
  }
  CodebookRow demographic_participant = participant;
  demographic_participant.file = "demographics.csv";
  rows->push_back(demographic_participant);
  for (const DemographicField& f : protocol.demographics) {
    CodebookRow row = variableRow("demographics.csv", f.id, "text", "NA",
                                  "the participant's answer; NA: skipped");
    row.text_en = f.label;
    if (f.kind == DemographicField::Kind::kInteger) {
      row.type = "integer";
      row.scale_min = std::to_string(f.min);
      row.scale_max = std::to_string(f.max);
    } else if (f.kind == DemographicField::Kind::kChoice) {
      row.type = "category";
      row.anchors = joined(f.choices, "; ");
    }
    rows->push_back(row);
  }
  for (const FreeTextQuestion& q : protocol.free_text) {
    CodebookRow row = variableRow("demographics.csv", q.id, "text", "NA",
                                  "the participant's free-text comment; NA: none given");
    row.text_en = q.prompt;
    rows->push_back(row);
  }
}

}  // namespace

std::vector<std::string> csvHeaderColumns(void (*write_header)(std::ostream&)) {
  std::ostringstream out;
  write_header(out);
  std::string line = out.str();
  line = line.substr(0, line.find('\n'));
  std::vector<std::string> columns;
  for (size_t at = 0; at <= line.size();) {
    const size_t comma = std::min(line.find(',', at), line.size());
    columns.push_back(line.substr(at, comma - at));
    at = comma + 1;
  }
  return columns;
}

std::vector<CodebookRow> studyCodebook(const StudyProtocol& protocol) {
  std::vector<CodebookRow> rows;
  addAnswerRows(protocol, &rows);
  for (const TableColumns& table : kTables)
    for (const std::string& column : csvHeaderColumns(table.write_header))
      rows.push_back(columnRow(table, column));
  return rows;
}

void writeCodebookCsv(std::ostream& out, const std::vector<CodebookRow>& rows) {
  out << "file,variable,type,unit,meaning,text_en,text_zh,scale_min,scale_max,anchors,construct,"
         "section\n";
  for (const CodebookRow& r : rows) {
    for (const std::string* field :
         {&r.file, &r.variable, &r.type, &r.unit, &r.meaning, &r.text_en, &r.text_zh, &r.scale_min,
          &r.scale_max, &r.anchors, &r.construct})
      out << csvFieldOrMissing(*field) << ',';
    out << csvFieldOrMissing(r.section) << '\n';
  }
}

}  // namespace cb
