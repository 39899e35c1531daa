#include "app/study/study_report_html.h"

#include <algorithm>
#include <cstdio>

#include "app/study/svg_charts.h"

namespace cb {
namespace {

std::string fixed(double v, int digits) {
  char text[40];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

std::string sdText(const std::optional<double>& sd) {
  return sd ? fixed(*sd, 2) : "–";
}

// NA, never 0.00, when nobody answered.
std::string meanText(const std::optional<double>& mean) {
  return mean ? fixed(*mean, 2) : "NA";
}

// A text cell (left-aligned; numbers are right-aligned).
std::string cell(const std::string& text) {
  return "<td class=\"t\">" + htmlEscape(text) + "</td>";
}

std::string itemTable(const StudyReport& report, int scale_min) {
  std::string html = "<table><tr><th>item</th><th>n</th>";
  const size_t points = report.items.empty() ? 0 : report.items.front().counts.size();
  for (size_t k = 0; k < points; ++k) html += "<th>" + std::to_string(scale_min + int(k)) + "</th>";
  html += "<th>mean</th><th>SD</th></tr>\n";
  for (const ItemSummary& item : report.items) {
    html += "<tr><td>" + htmlEscape(item.item) + "</td><td>" + std::to_string(item.n) + "</td>";
    for (size_t count : item.counts) html += "<td>" + std::to_string(count) + "</td>";
    html += "<td>" + meanText(item.mean) + "</td><td>" + sdText(item.sd) + "</td></tr>\n";
  }
  return html + "</table>\n";
}

std::string constructTable(const StudyReport& report) {
  std::string html =
      "<table><tr><th>construct</th><th>items</th><th>participants</th><th>mean</th><th>SD</th>"
      "</tr>\n";
  for (const ConstructSummary& c : report.constructs) {
    std::string items;
    for (const std::string& id : c.definition.items) items += (items.empty() ? "" : " ") + id;
    html += "<tr>" + cell(c.definition.name) + cell(items) + "<td>" +
            std::to_string(c.participants) + "</td><td>" + meanText(c.mean) + "</td><td>" +
            sdText(c.sd) + "</td></tr>\n";
  }
  html += "</table>\n";
  for (const ConstructSummary& c : report.constructs) {
    if (c.missing_items.empty()) continue;
    std::string items;
    for (const std::string& id : c.missing_items) items += (items.empty() ? "" : ", ") + id;
    html += "<p class=\"problem\">" + htmlEscape(c.definition.name) + ": the answers have no " +
            htmlEscape(items) + (c.mean ? " (the figures use its other items)" : "") + ".</p>\n";
  }
  return html;
}

std::string pairedSection(const StudyReport& report, const StudyReportOptions& options) {
  std::string html = "<h2>Paired comparison: " + htmlEscape(options.paired_first) + " vs " +
                     htmlEscape(options.paired_second) + "</h2>\n";
  if (!report.paired)
    return html + "<p class=\"problem\">" + htmlEscape(report.paired_problem) + "</p>\n";
  const PairedTTest& t = *report.paired;
  html += "<p>Paired t-test over the " + std::to_string(t.n) +
          " participants who answered both (Student 1908; as in the thesis §7.7.2, where Q3 "
          "rates the 2D brush and Q6 the 3D brush). Alternative: " +
          htmlEscape(t.second) + " is rated higher than " + htmlEscape(t.first) + ".</p>\n";
  html += "<table><tr><th>" + htmlEscape(t.first) + " mean</th><th>" + htmlEscape(t.second) +
          " mean</th><th>mean difference</th><th>SD of differences</th><th>t</th><th>df</th>"
          "<th>p (one-tailed)</th><th>p (two-tailed)</th></tr>\n<tr><td>" +
          fixed(t.mean_first, 2) + "</td><td>" + fixed(t.mean_second, 2) + "</td><td>" +
          fixed(t.mean_difference, 3) + "</td><td>" + fixed(t.sd_difference, 3) + "</td><td>" +
          fixed(t.t, 3) + "</td><td>" + fixed(t.degrees_of_freedom, 0) + "</td><td>" +
          fixed(t.p_one_tailed, 3) + "</td><td>" + fixed(t.p_two_tailed, 3) +
          "</td></tr></table>\n";
  return html;
}

std::string setApartSection(const StudyReport& report) {
  if (report.set_apart.empty()) return "";
  std::string html =
      "<h2>Set apart</h2>\n<p>Not counted as participants: their answers are left out of every "
      "questionnaire statistic below (their trials and session figures are still shown under "
      "Tasks and Sessions).</p>\n"
      "<table><tr><th>participant</th><th>session</th><th>why</th></tr>\n";
  for (const SetApartParticipant& p : report.set_apart)
    html += "<tr>" + cell(p.participant) + cell(p.session.empty() ? "–" : p.session) + cell(p.why) +
            "</tr>\n";
  return html + "</table>\n";
}

std::string robustText(const std::optional<RobustSummary>& s, int digits) {
  if (!s) return "<td>NA</td><td>NA</td><td>NA</td>";
  return "<td>" + fixed(s->median, digits) + "</td><td>" + fixed(s->q1, digits) + "–" +
         fixed(s->q3, digits) + "</td><td>" + fixed(s->min, digits) + "–" + fixed(s->max, digits) +
         "</td>";
}

std::string taskSummaryTable(const StudyReport& report) {
  std::string html =
      "<table><tr><th>task</th><th>trials</th><th>median duration (s)</th><th>IQR (s)</th>"
      "<th>range (s)</th><th>median strokes</th><th>ended</th></tr>\n";
  for (const TaskSummary& t : report.tasks) {
    std::string ended;
    for (const auto& [reason, n] : t.end_reasons)
      ended += (ended.empty() ? "" : ", ") + reason + " " + std::to_string(n);
    html += "<tr>" + cell(t.task) + "<td>" + std::to_string(t.trials) + "</td>" +
            robustText(t.duration_s, 1) + "<td>" +
            (t.strokes ? fixed(t.strokes->median, 1) : std::string("NA")) + "</td>" + cell(ended) +
            "</tr>\n";
  }
  return html + "</table>\n";
}

std::string trialTable(const StudyReport& report) {
  std::string html =
      "<table><tr><th>participant</th><th>session</th><th>task</th><th>order</th>"
      "<th>onset (s after the session's start)</th><th>duration "
      "(s)</th><th>ended</th><th>strokes</th><th>erases</th>"
      "<th>undos</th></tr>\n";
  for (const SessionFigures& s : report.sessions)
    for (const TrialRow& t : s.trials) {
      const double onset = s.outcome.start_ns
                               ? double(elapsedNs(t.onset_ns, *s.outcome.start_ns)) * 1e-9
                               : double(t.onset_ns) * 1e-9;
      html += "<tr>" + cell(s.participant.empty() ? "NA" : s.participant) + cell(s.id) +
              cell(t.task) + "<td>" + std::to_string(t.order) + "</td><td>" + fixed(onset, 1) +
              "</td><td>" + (t.duration_s ? fixed(*t.duration_s, 1) : std::string("NA")) + "</td>" +
              cell(t.end_reason.empty() ? "unfinished" : t.end_reason) + "<td>" +
              std::to_string(t.strokes) + "</td><td>" + std::to_string(t.erases) + "</td><td>" +
              std::to_string(t.undos) + "</td></tr>\n";
    }
  return html + "</table>\n";
}

std::string taskSection(const StudyReport& report) {
  if (report.tasks.empty()) return "";
  std::vector<std::string> labels;
  std::vector<std::vector<double>> durations;
  std::vector<double> medians;
  for (const TaskSummary& t : report.tasks) {
    labels.push_back(t.task);
    durations.emplace_back();
    for (const SessionFigures& s : report.sessions)
      for (const TrialRow& r : s.trials)
        if (r.task == t.task && r.duration_s) durations.back().push_back(*r.duration_s);
    medians.push_back(t.duration_s ? t.duration_s->median : 0.0);
  }
  return "<h2>Tasks</h2>\n<p>Each trial's duration is the task's stage clock (operator pauses "
         "and a restarted runner's downtime not counted) until it ended: time-up, done (the "
         "participant's \"I'm done\"), skipped or aborted by the operator; NA when the journal "
         "ends inside the task. Medians and quartiles (Hyndman &amp; Fan type 7) over every "
         "session given, set-apart sessions included.</p>\n" +
         dotStripSvg(labels, durations, medians, "Task durations (dots: trials; bar: median)",
                     "s") +
         taskSummaryTable(report) + "<h3>Trials per participant</h3>\n" + trialTable(report);
}

std::string sessionTable(const StudyReport& report) {
  std::string html =
      "<table><tr><th>session</th><th>participant</th><th>status</th><th>duration (s)</th>"
      "<th>down (s)</th><th>samples</th><th>strokes</th><th>tip down (s)</th>"
      "<th>median speed (mm/s)</th><th>IQR (mm/s)</th><th>outliers</th></tr>\n";
  for (const SessionFigures& s : report.sessions) {
    const SessionOutcome& o = s.outcome;
    html += "<tr>" + cell(s.id) + cell(s.participant.empty() ? "NA" : s.participant) +
            cell(o.status + (o.reason.empty() ? "" : " (" + o.reason + ")")) + "<td>" +
            fixed(o.duration_s, 1) + "</td><td>" + fixed(double(o.down_ns) * 1e-9, 1) +
            "</td><td>" + std::to_string(s.samples) + "</td><td>" + std::to_string(s.strokes) +
            "</td><td>" + fixed(s.tip_down_s, 1) + "</td><td>" +
            (s.speed ? fixed(s.speed->median, 1) : std::string("NA")) + "</td><td>" +
            (s.speed ? fixed(s.speed->q1, 1) + "–" + fixed(s.speed->q3, 1) : std::string("NA")) +
            "</td><td>" + std::to_string(s.speed_outliers.size()) + "</td></tr>\n";
  }
  return html + "</table>\n";
}

std::string outlierText(const StrokeOutlier& o) {
  return "stroke " + std::to_string(o.stroke) + " at " + fixed(o.start_s, 2) + " s" +
         (o.task.empty() ? std::string() : " (task " + o.task + ")") + ": " +
         fixed(o.speed_mm_s, 0) + " mm/s";
}

// A session's charts: pressure, and stroke speed on a scale that ends at the outer fence.
std::string sessionCharts(const SessionFigures& s) {
  std::string html = "<h3>" + htmlEscape(s.id) + "</h3>\n";
  // Pen sample -> present latency, frame intervals and missed refreshes (Frame records).
  html += "<pre>" + htmlEscape(formatFrameTimingStats(s.timing, "")) + "</pre>\n";
  if (s.samples == 0) return html + "<p>No pen samples.</p>\n";
  html +=
      timeSeriesSvg(s.pressure_t, s.pressure, "pressure while the tip is down", "0..1", 0.0, 1.0);
  if (!s.speed) return html;
  std::vector<size_t> beyond;
  std::vector<std::string> titles;
  for (const StrokeOutlier& o : s.speed_outliers) {
    beyond.push_back(o.point);
    titles.push_back(outlierText(o));
  }
  // The scale ends at the fastest stroke that is not an outlier.
  double top = 0;
  for (size_t i = 0; i < s.stroke_speed.size(); ++i)
    if (std::find(beyond.begin(), beyond.end(), i) == beyond.end())
      top = std::max(top, s.stroke_speed[i]);
  // 10 % headroom, so the fastest ordinary stroke does not sit on the frame.
  html += scatterSvg(s.stroke_start_s, s.stroke_speed, "mean speed per stroke", "mm/s", top * 1.1,
                     beyond, titles);
  if (s.speed_outliers.empty()) return html;
  html += "<p>Outliers beyond Tukey's outer fence (" + fixed(s.speed->high_fence, 1) +
          " mm/s = Q3 + 3·IQR), drawn as red marks at the top, off the chart's scale:</p>\n<ul>";
  for (const StrokeOutlier& o : s.speed_outliers)
    html += "<li>" + htmlEscape(outlierText(o)) + "</li>";
  return html + "</ul>\n";
}

std::string sessionSection(const StudyReport& report) {
  if (report.sessions.empty()) return "";
  std::string html =
      "<h2>Sessions</h2>\n<p>Duration is the session's own clock, from the runner's start "
      "record to its end record (a journal that is not a study session: first to last record), "
      "less the time a restarted runner was down. Stroke speed is path length / duration per "
      "stroke that moved (taps and dabs left out); median and quartiles resist a single "
      "artefact, which is named below its chart.</p>"
      "\n" +
      sessionTable(report);
  for (const SessionFigures& s : report.sessions) html += sessionCharts(s);
  return html;
}

}  // namespace

std::string studyReportHtml(const StudyReport& report, const StudyReportOptions& options,
                            int scale_min, int scale_max) {
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>" +
      htmlEscape(options.title) +
      "</title>\n<style>body{font-family:sans-serif;max-width:60em;margin:1em auto;padding:0 1em}"
      "table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ccc;padding:2px 6px;"
      "text-align:right}td:first-child,th:first-child,td.t{text-align:left}.problem{color:#a00}pre{"
      "white-space:pre-wrap}"
      "</style></head><body>\n";
  html += "<h1>" + htmlEscape(options.title) + "</h1>\n";
  html +=
      "<p>Answers: " + htmlEscape(options.answers_name) + " — " +
      std::to_string(report.participants) + " participants counted" +
      (report.set_apart.empty()
           ? std::string()
           : " (" + std::to_string(report.set_apart.size()) + " set apart, listed below)") +
      ", " + std::to_string(report.items.size()) + " items on a " + std::to_string(scale_min) +
      ".." + std::to_string(scale_max) +
      " scale. Means and sample standard deviations (n − 1); missing answers are left out, and an "
      "item nobody answered has the mean NA.</p>\n";
  if (report.sessions.empty())
    html +=
        "<p>No session journals were given, so who completed a session is not known here: only "
        "participants who answered no item are set apart. Give the sessions' journals to set "
        "aborted and declined sessions apart too.</p>\n";
  html += setApartSection(report);
  html += "<h2>Answers per item</h2>\n" + likertStackedBarsSvg(report.items, scale_min) +
          itemTable(report, scale_min);
  if (!report.constructs.empty()) {
    html += "<h2>Constructs</h2>\n<p>";
    if (!options.constructs_source.empty()) html += htmlEscape(options.constructs_source) + ". ";
    html +=
        "Each participant's score is the mean of the construct's items they answered; the "
        "table gives the mean and SD of those scores.</p>\n" +
        constructMeansSvg(report.constructs, scale_min, scale_max) + constructTable(report);
  }
  html += pairedSection(report, options);
  html += taskSection(report);
  html += sessionSection(report);
  return html + "</body></html>\n";
}

}  // namespace cb
