#include "app/study/export_columns.h"

#include <cctype>
#include <stdexcept>

namespace cb {
namespace {

using Levels = std::vector<std::pair<std::string, std::string>>;

const ExportColumn kParticipant = {
    "participant",
    "text",
    "",
    "The participant's pseudonymous code in the study (the runner's study.info record); NA "
    "outside a study",
    {}};
const ExportColumn kSession = {
    "session",
    "text",
    "",
    "The session's id: a study session's folder name <participant>-<UTC start>, else the "
    "journal's file name",
    {}};
const ExportColumn kTask = {
    "task",
    "text",
    "",
    "The study task running when the row was recorded (the protocol's task id); NA outside tasks",
    {}};

const Levels kEndReasons = {{"time-up", "the task's time limit passed"},
                            {"done", "the participant tapped \"I'm done\" and confirmed it"},
                            {"skipped", "the operator skipped the task (reason in the journal)"},
                            {"aborted", "the operator aborted the session during the task"},
                            {"other", "another reason the runner recorded"}};

}  // namespace

const std::vector<ExportColumn>& trialColumns() {
  static const std::vector<ExportColumn> columns = {
      kParticipant,
      kSession,
      {"task", "text", "", "The id of the painting task in the study protocol", {}},
      {"order",
       "integer",
       "",
       "The task's position in the participant's counterbalanced task order (1 = first)",
       {}},
      {"onset_s",
       "number",
       "s",
       "When the task began, seconds after the journal's first record",
       {}},
      {"onset_monotonic_ns",
       "integer",
       "ns",
       "When the task began, on the recording machine's monotonic clock (the journal's "
       "timestamps)",
       {}},
      {"onset_wall_clock_unix_ns",
       "integer",
       "ns",
       "When the task began, as UTC wall-clock time since 1970-01-01 (from the session's "
       "monotonic-to-wall-clock anchor); NA when the journal has no anchor",
       {}},
      {"duration_s",
       "number",
       "s",
       "How long the task ran on the stage clock until it closed, which counts neither operator "
       "pauses nor the time a restarted runner was down; NA when the task never closed",
       {}},
      {"end_reason", "category", "", "How the task ended; NA when the journal ends inside the task",
       kEndReasons},
      {"strokes",
       "integer",
       "strokes",
       "Strokes the painter mapped into the cloud in paint mode during the task",
       {}},
      {"erases", "integer", "strokes", "Rub-out strokes and vacuum cuts during the task", {}},
      {"undos", "integer", "count", "Undo commands during the task", {}}};
  return columns;
}

const std::vector<ExportColumn>& strokeColumns() {
  static const std::vector<ExportColumn> columns = {
      kParticipant,
      kSession,
      {"gesture",
       "integer",
       "",
       "The row's number in the session, 0-based in time order (a run of tip-down samples, cut "
       "where the painter began a stroke)",
       {}},
      {"kind",
       "category",
       "",
       "What the painter made of the row's tip-down run",
       {{"stroke", "a stroke mapped into the cloud"},
        {"erase", "a drag in erase mode"},
        {"menu_tap", "the pen on the on-screen UI (a menu or form)"},
        {"camera", "a drag in camera mode"},
        {"canvas", "a drag in canvas mode"},
        {"light", "a drag in light mode"},
        {"unmapped", "a touch in paint mode that made no stroke"}}},
      {"stroke",
       "integer",
       "",
       "The painter's stroke index, as in the journal's StrokeMapped records and sync markers "
       "(kind stroke); NA for other kinds",
       {}},
      {"start_s",
       "number",
       "s",
       "The stroke's first tip-down sample, seconds after the session's first journal record",
       {}},
      {"duration_s", "number", "s", "Last minus first tip-down sample", {}},
      {"samples", "integer", "samples", "Tip-down samples in the stroke", {}},
      {"path_length_mm",
       "number",
       "mm",
       "Sum of distances between consecutive tip-down samples, on the tablet's surface",
       {}},
      {"mean_pressure",
       "number",
       "fraction 0..1",
       "Mean pressure over the stroke, normalised by the device's maximum",
       {}},
      {"max_pressure", "number", "fraction 0..1", "Highest pressure in the stroke", {}},
      {"mean_tilt_deg", "number", "deg", "Mean angle of the pen from vertical (90 - altitude)", {}},
      {"speed_mm_s",
       "number",
       "mm/s",
       "Path length / duration; NA for a stroke of one sample (no duration)",
       {}},
      {"brush",
       "category",
       "",
       "The brush selected when the stroke began; NA when none recorded",
       {}},
      {"mode",
       "category",
       "",
       "The painter's mode when the stroke began; NA when none recorded",
       {{"paint", "painting clouds"},
        {"erase", "rubbing out"},
        {"camera", "moving the view"},
        {"canvas", "moving the drawing plane"},
        {"light", "moving the light"}}},
      {"mapping_ms",
       "number",
       "ms",
       "Time the painter took to map the stroke into the cloud; NA in journals without it",
       {}},
      kTask};
  return columns;
}

const std::vector<ExportColumn>& sampleColumns() {
  static const std::vector<ExportColumn> columns = {
      kParticipant,
      kSession,
      {"sample", "integer", "", "Sample number in the session, 0-based in time order", {}},
      {"t_ns",
       "integer",
       "ns",
       "The pen report's time on the monotonic clock (the kernel's time of the report, the "
       "journal's timestamp)",
       {}},
      {"t_s",
       "number",
       "s",
       "The pen report's time after the journal's first record; the tablet reports when the pen "
       "moves, so intervals vary",
       {}},
      {"x_raw",
       "integer",
       "device units",
       "Pen x as the tablet reports it, from the active area's left edge",
       {}},
      {"y_raw",
       "integer",
       "device units",
       "Pen y as the tablet reports it, from the active area's top edge",
       {}},
      {"x_mm",
       "number",
       "mm",
       "Pen tip position across the tablet's active area from its left edge, +x right (x_raw / "
       "resolution)",
       {}},
      {"y_mm",
       "number",
       "mm",
       "Pen tip position down the tablet's active area from its top edge, +y towards the user "
       "(y_raw / resolution)",
       {}},
      {"pressure_raw", "integer", "device units", "Tip pressure as the tablet reports it", {}},
      {"pressure",
       "number",
       "fraction 0..1",
       "Tip pressure normalised to 0..1 by the device's maximum",
       {}},
      {"tilt_x_raw", "integer", "device units", "Tilt towards +x as the tablet reports it", {}},
      {"tilt_y_raw", "integer", "device units", "Tilt towards +y as the tablet reports it", {}},
      {"tilt_x_deg",
       "number",
       "deg",
       "Pen tilt from vertical in the x-z plane, +x to the right (0 when the tablet reports no "
       "tilt)",
       {}},
      {"tilt_y_deg",
       "number",
       "deg",
       "Pen tilt from vertical in the y-z plane, +y towards the user (0 when the tablet reports "
       "no tilt)",
       {}},
      {"distance_raw",
       "integer",
       "device units",
       "Hover distance above the surface as the tablet reports it",
       {}},
      {"distance",
       "number",
       "fraction 0..1",
       "Hover distance normalised: 0 touching, 1 the edge of proximity",
       {}},
      {"buttons",
       "integer",
       "bit mask",
       "Button bits: 1 tip in contact, 2 lower barrel button, 4 upper barrel button",
       {}},
      {"tip", "integer", "0/1", "1 while the device reports the tip in contact, else 0", {}},
      {"in_proximity",
       "integer",
       "0/1",
       "1 while the pen is within the tablet's sensing range",
       {}},
      {"tool",
       "category",
       "",
       "The tool in range",
       {{"none", "no tool in range"},
        {"pen", "the pen's tip end"},
        {"eraser", "the pen's eraser end"}}},
      {"tool_id", "integer", "", "The tool's type id as the tablet reports it (0: unknown)", {}},
      {"tool_serial",
       "integer",
       "",
       "The tool's serial number as the tablet reports it (0: unknown)",
       {}},
      {"gesture",
       "integer",
       "",
       "The gesture (strokes.csv row) the sample belongs to; NA between gestures",
       {}},
      {"stroke",
       "integer",
       "",
       "The painter's stroke index of the sample's gesture (kind stroke); NA otherwise",
       {}},
      kTask};
  return columns;
}

const std::vector<ExportColumn>& eventColumns() {
  static const std::vector<ExportColumn> columns = {
      kParticipant,
      kSession,
      {"t_s", "number", "s", "The record's time, seconds after the journal's first record", {}},
      {"record", "integer", "", "The record's position in the journal (0 = first)", {}},
      {"kind",
       "category",
       "",
       "The record's kind (drivers/core/JOURNAL.md; type-N: a type this build does not know)",
       {{"mode", "a mode change"},
        {"ui", "a UI change"},
        {"marker", "a note or a study runner's marker"},
        {"calibration", "the calibration in force"},
        {"session", "the session's starting state"},
        {"device", "the pen device"},
        {"settings", "a configuration file in force"},
        {"stroke_mapped", "the painter mapped a stroke"},
        {"sync", "a synchronisation pulse"},
        {"frame", "a presented frame's timing"}}},
      {"key", "text", "", "ui: the change's name (left of '='); mode: \"mode\"; else NA", {}},
      {"value",
       "text",
       "",
       "ui: the change's value; mode: the mode; marker and others: the record's text",
       {}},
      kTask};
  return columns;
}

const std::vector<ExportColumn>& bidsEventColumns() {
  static const std::vector<ExportColumn> columns = [] {
    std::vector<ExportColumn> c = {
        {"onset",
         "number",
         "s",
         "When the event began, after the journal's first record (the pen motion recording's "
         "latency 0)",
         {}},
        {"duration",
         "number",
         "s",
         "Recording time from the event's beginning to its end, operator pauses included; NA "
         "when the recording ends before it does",
         {}},
        {"trial_type",
         "category",
         "",
         "The stage of the study session (a row per stage, in the protocol's order), or an "
         "operator pause",
         {{"consent", "the consent page"},
          {"participant", "the participant's code is entered"},
          {"introduction", "the introduction page"},
          {"tutorial", "the guided tutorial on the painter"},
          {"free-drawing", "free drawing on the painter"},
          {"task", "a painting task (the task column names it)"},
          {"demographics", "the demographic questions"},
          {"questionnaire", "the Likert questionnaire"},
          {"free-text", "the free-text questions"},
          {"pause", "the operator paused the session (the stage clock stops)"}}}};
    for (const char* name :
         {"task", "order", "duration_s", "end_reason", "strokes", "erases", "undos"}) {
      ExportColumn t = exportColumn(trialColumns(), name);
      t.description[0] = char(std::tolower(static_cast<unsigned char>(t.description[0])));
      t.description = "For task rows, " + t.description;
      if (t.name == "duration_s") t.name = "active_duration";
      c.push_back(t);
    }
    c.push_back(
        {"operator_reason", "text", "", "For pause rows, the reason the operator chose", {}});
    return c;
  }();
  return columns;
}

const ExportColumn& exportColumn(const std::vector<ExportColumn>& table, const std::string& name) {
  for (const ExportColumn& c : table)
    if (c.name == name) return c;
  throw std::out_of_range("no exported column '" + name + "'");
}

std::string csvHeaderLine(const std::vector<ExportColumn>& table) {
  std::string line;
  for (const ExportColumn& c : table) line += (line.empty() ? "" : ",") + c.name;
  return line + '\n';
}

std::string bidsUnit(const std::string& unit) {
  for (const char* si : {"s", "ns", "ms", "mm", "mm/s", "deg"})
    if (unit == si) return unit;
  return "";
}

}  // namespace cb
