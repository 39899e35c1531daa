#include "app/study/codebook.h"

#include <sstream>

#include "app/study/csv_text.h"
#include "app/study/trace_csv.h"
#include "app/study/trial_table.h"

namespace cb {
namespace {

// One column of a table the exports write: its type, unit (NA: none) and meaning.
struct ColumnMeaning {
  const char* name;
  const char* type;
  const char* unit;
  const char* meaning;
};

// Columns every pen-trace and trial table begins with.
const ColumnMeaning kSessionColumns[] = {
    {"participant", "text", "NA",
     "the participant's pseudonymous id (the runner's study.info record); NA outside a study"},
    {"session", "text", "NA",
     "the session's id: a study session's folder name <participant>-<UTC start>, else the "
     "journal's file name"},
    {"task", "text", "NA",
     "the study task running when the row was recorded (the protocol's task id); NA outside "
     "tasks"},
};

const ColumnMeaning kTrialColumns[] = {
    {"order", "integer", "NA", "the task's position in the participant's task order (1 = first)"},
    {"onset_s", "number", "s", "task start, seconds after the session's first journal record"},
    {"onset_monotonic_ns", "integer", "ns",
     "task start on the machine's monotonic clock (the journal's timestamps)"},
    {"onset_wall_clock_unix_ns", "integer", "ns",
     "task start as UTC wall-clock time, nanoseconds since 1970-01-01 (from the session's clock "
     "anchor); NA when the journal has no anchor"},
    {"duration_s", "number", "s",
     "time painted on the stage clock until the task closed (pauses and a resumed session's "
     "downtime not counted); NA when the task never closed"},
    {"end_reason", "category", "NA",
     "how the task ended: time-up (its limit), done (the participant's \"I'm done\"), skipped "
     "(the operator), aborted (the operator ended the session), NA (the journal ends inside the "
     "task)"},
    {"strokes", "integer", "strokes",
     "paint strokes the painter mapped into the cloud in the task"},
    {"erases", "integer", "strokes", "rub-out strokes and vacuum cuts in the task"},
    {"undos", "integer", "count", "undo commands in the task"},
};

const ColumnMeaning kStrokeColumns[] = {
    {"gesture", "integer", "NA",
     "the row's number in the session, 0-based in time order (a run of tip-down samples, cut "
     "where the painter began a stroke)"},
    {"kind", "category", "NA",
     "what the painter made of it: stroke (mapped into the cloud), erase (a drag in erase "
     "mode), menu_tap (the pen on the on-screen UI), camera, canvas, light (a drag in that "
     "mode), unmapped (a touch in paint mode that made no stroke)"},
    {"stroke", "integer", "NA",
     "the painter's stroke index, as in the journal's StrokeMapped and sync markers (kind "
     "stroke); NA for other kinds"},
    {"start_s", "number", "s",
     "the stroke's first tip-down sample, seconds after the session's first journal record"},
    {"duration_s", "number", "s", "last minus first tip-down sample"},
    {"samples", "integer", "samples", "tip-down samples in the stroke"},
    {"path_length_mm", "number", "mm",
     "sum of distances between consecutive tip-down samples, on the tablet's surface"},
    {"mean_pressure", "number", "fraction 0..1",
     "mean pressure over the stroke, normalised by the device's maximum"},
    {"max_pressure", "number", "fraction 0..1", "highest pressure in the stroke"},
    {"mean_tilt_deg", "number", "deg", "mean angle of the pen from vertical (90 - altitude)"},
    {"speed_mm_s", "number", "mm/s",
     "path length / duration; NA for a stroke of one sample (no duration)"},
    {"brush", "category", "NA", "the brush selected when the stroke began; NA when none recorded"},
    {"mode", "category", "NA",
     "the painter's mode when the stroke began (paint, erase, camera, canvas, light); NA when "
     "none recorded"},
    {"mapping_ms", "number", "ms",
     "time the painter took to map the stroke into the cloud; NA in journals without it"},
};

const ColumnMeaning kSampleColumns[] = {
    {"sample", "integer", "NA", "sample number in the session, 0-based in time order"},
    {"t_ns", "integer", "ns", "the sample's time on the monotonic clock (the journal's timestamp)"},
    {"t_s", "number", "s", "seconds after the session's first journal record"},
    {"x_raw", "integer", "device units",
     "pen x as the tablet reports it, from the active area's left edge"},
    {"y_raw", "integer", "device units",
     "pen y as the tablet reports it, from the active area's top edge"},
    {"x_mm", "number", "mm", "pen x from the active area's left edge (x_raw / resolution)"},
    {"y_mm", "number", "mm", "pen y from the active area's top edge (y_raw / resolution)"},
    {"pressure_raw", "integer", "device units", "tip pressure as the tablet reports it"},
    {"pressure", "number", "fraction 0..1", "pressure_raw / the device's maximum pressure"},
    {"tilt_x_raw", "integer", "device units", "tilt towards +x as the tablet reports it"},
    {"tilt_y_raw", "integer", "device units", "tilt towards +y as the tablet reports it"},
    {"tilt_x_deg", "number", "deg", "tilt from vertical, positive to the right"},
    {"tilt_y_deg", "number", "deg", "tilt from vertical, positive towards the user"},
    {"distance_raw", "integer", "device units",
     "hover distance above the surface as the tablet reports it"},
    {"distance", "number", "fraction 0..1",
     "hover distance normalised: 0 touching, 1 the edge of proximity"},
    {"buttons", "integer", "bit mask",
     "1 = tip in contact, 2 = lower barrel button, 4 = upper barrel button"},
    {"tip", "integer", "0/1", "1 while the device reports the tip in contact"},
    {"in_proximity", "integer", "0/1", "1 while the pen is within the tablet's sensing range"},
    {"tool", "category", "NA", "pen, eraser (the pen's other end) or none"},
    {"tool_id", "integer", "NA", "the tool's type id as the tablet reports it (0: unknown)"},
    {"tool_serial", "integer", "NA",
     "the tool's serial number as the tablet reports it (0: unknown)"},
    {"gesture", "integer", "NA",
     "the gesture (strokes.csv row) the sample belongs to; NA between gestures"},
    {"stroke", "integer", "NA",
     "the painter's stroke index of the sample's gesture (kind stroke); NA otherwise"},
};

const ColumnMeaning kEventColumns[] = {
    {"t_s", "number", "s", "seconds after the session's first journal record"},
    {"record", "integer", "NA", "the record's position in the journal (0 = first)"},
    {"kind", "category", "NA",
     "the record's kind: mode, ui, marker, calibration, session, device, settings, "
     "stroke_mapped, sync, frame (type-N: unknown)"},
    {"key", "text", "NA", "ui: the change's name (left of '='); mode: \"mode\"; else NA"},
    {"value", "text", "NA",
     "ui: the change's value; mode: the mode; marker and others: the record's text "
     "(drivers/core/JOURNAL.md)"},
};

struct TableColumns {
  const char* file;
  void (*write_header)(std::ostream&);
  const ColumnMeaning* begin;
  const ColumnMeaning* end;
};

const TableColumns kTables[] = {
    {"trials.csv", writeTrialsCsvHeader, std::begin(kTrialColumns), std::end(kTrialColumns)},
    {"strokes.csv", writeStrokesCsvHeader, std::begin(kStrokeColumns), std::end(kStrokeColumns)},
    {"samples.csv", writeSamplesCsvHeader, std::begin(kSampleColumns), std::end(kSampleColumns)},
    {"events.csv", writeEventsCsvHeader, std::begin(kEventColumns), std::end(kEventColumns)},
};

CodebookRow columnRow(const TableColumns& table, const std::string& column) {
  CodebookRow row;
  row.file = table.file;
  row.variable = column;
  for (const ColumnMeaning* c = table.begin; c != table.end; ++c)
    if (column == c->name) row.type = c->type, row.unit = c->unit, row.meaning = c->meaning;
  for (const ColumnMeaning& c : kSessionColumns)
    if (column == c.name) row.type = c.type, row.unit = c.unit, row.meaning = c.meaning;
  return row;  // an unknown column keeps an empty meaning (the codebook test refuses it)
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
      variableRow("questionnaire.csv", "participant", "text", "NA", kSessionColumns[0].meaning);
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
